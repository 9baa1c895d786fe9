#include "renderer/scene/media_builder.h"

#include <limits>
#include <stdexcept>

namespace vesper {
namespace {

// render -> index = (T ∘ G)^-1 ∘ (r * unit_scale + origin)
Transformf render_to_index(const Transform& t, const DensityGrid& grid, const Vec3d& origin,
                           double unit_scale) {
  const Transform world_from_index = t * grid.index_to_world();
  if (!world_from_index.invertible())
    throw std::runtime_error("grid '" + grid.name() + "' has a singular transform");
  const Transform world_from_render =
      Transform::translate(origin) * Transform::scale(Vec3d(unit_scale));
  return (inverse(world_from_index) * world_from_render).cast<float>();
}

std::shared_ptr<const MajorantGrid> majorants_of(const DensityGrid& grid,
                                                 const MediaBuildOptions& options) {
  return std::make_shared<MajorantGrid>(options.majorant_grid
                                            ? MajorantGrid(grid, options.majorant_cell_voxels)
                                            : MajorantGrid::global(grid));
}

Box3 render_box(const BoxDesc& b, const Vec3d& origin, double unit_scale) {
  return {Vec3((b.min - origin) / unit_scale), Vec3((b.max - origin) / unit_scale)};
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
        m.bounds = render_box(*h->bounds, origin, unit_scale);
        for (const BoxDesc& b : h->bounds_steps)
          m.bounds_steps.push_back(render_box(b, origin, unit_scale));
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
    g.majorants = majorants_of(*v.density, options);
    for (const Transform& t : v.transform_steps)  // motion blur
      g.index_steps.push_back(render_to_index(t, *v.density, origin, unit_scale));
    g.density_scale = float(v.density_scale);
    g.sigma_a = v.sigma_a * per_render_unit;
    g.sigma_s = v.sigma_s * per_render_unit;
    g.g = float(v.g);
    if (v.emission && v.emission_scale > 0) {
      g.emission = v.emission;
      g.render_to_emission_index = render_to_index(v.transform, *v.emission, origin, unit_scale);
      g.emission_majorants = majorants_of(*v.emission, options);
      for (const Transform& t : v.transform_steps)
        g.emission_index_steps.push_back(render_to_index(t, *v.emission, origin, unit_scale));
      g.emission_coefficient = v.emission_color * float(v.emission_scale * unit_scale);
    }
    if (g.density_scale > 0.f || g.emission) media.push_back(std::move(g));
  }
  return MediaSet(std::move(media));
}

}  // namespace vesper
