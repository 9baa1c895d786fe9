#include "renderer/scene/media_builder.h"

#include <limits>
#include <stdexcept>

#include "renderer/media/affine.h"

namespace vesper {
namespace {

Affine3f to_float(const Affine3d& a) {
  Affine3f f;
  for (int i = 0; i < 12; ++i) f.m[i] = float(a.m[size_t(i)]);
  return f;
}

// render -> index = (T ∘ G)^-1 ∘ (r * unit_scale + origin)
Affine3f render_to_index(const Transform& t, const DensityGrid& grid, const Vec3d& origin,
                         double unit_scale) {
  const Affine3d world_from_index =
      compose(affine_from_transform_rows(t.m.data()), grid.index_to_world());
  const auto index_from_world = inverse(world_from_index);
  if (!index_from_world)
    throw std::runtime_error("grid '" + grid.name() + "' has a singular transform");
  Affine3d world_from_render;
  world_from_render.m = {unit_scale, 0,        0, origin.x, 0,          unit_scale,
                         0,          origin.y, 0, 0,        unit_scale, origin.z};
  return to_float(compose(*index_from_world, world_from_render));
}

}  // namespace

MediaSet build_media(const SceneDescription& desc, const Vec3d& origin, double unit_scale,
                     const MediaBuildOptions& options) {
  std::vector<Medium> media;
  const float per_render_unit = float(unit_scale);  // sigma per world unit -> per render unit
  for (const MediumDesc& md : desc.media) {
    if (const auto* h = std::get_if<HomogeneousMediumDesc>(&md.medium)) {
      HomogeneousMedium m;
      m.sigma_a = h->sigma_a * per_render_unit;
      m.sigma_s = h->sigma_s * per_render_unit;
      m.g = float(h->g);
      if (h->bounds) {
        m.bounded = true;
        m.bounds.lo = Vec3((h->bounds->min - origin) / unit_scale);
        m.bounds.hi = Vec3((h->bounds->max - origin) / unit_scale);
      } else {
        constexpr float inf = std::numeric_limits<float>::infinity();
        m.bounds = {Vec3(-inf), Vec3(inf)};
      }
      if ((m.sigma_a + m.sigma_s).max_component() > 0.f) media.push_back(m);
      continue;
    }
    const auto& v = std::get<VdbMediumDesc>(md.medium);
    GridMedium g;
    g.density = v.density;
    g.render_to_index = render_to_index(v.transform, *v.density, origin, unit_scale);
    g.majorants = std::make_shared<MajorantGrid>(
        options.majorant_grid ? MajorantGrid(*v.density, options.majorant_cell_voxels)
                              : MajorantGrid::global(*v.density));
    g.density_scale = float(v.density_scale);
    g.sigma_a = v.sigma_a * per_render_unit;
    g.sigma_s = v.sigma_s * per_render_unit;
    g.g = float(v.g);
    if (v.emission && v.emission_scale > 0) {
      g.emission = v.emission;
      g.render_to_emission_index = render_to_index(v.transform, *v.emission, origin, unit_scale);
      g.emission_coefficient = v.emission_color * float(v.emission_scale * unit_scale);
    }
    if (g.density_scale > 0.f || g.emission) media.push_back(std::move(g));
  }
  return MediaSet(std::move(media));
}

}  // namespace vesper
