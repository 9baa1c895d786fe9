#include "renderer/integrator/photon_merging.h"

#include <cmath>
#include <vector>

#include "renderer/integrator/path_context.h"
#include "renderer/math/constants.h"
#include "renderer/media/henyey_greenstein.h"

namespace vesper {

float PhotonMerging::scale() const {
  const double r = double(map.radius());
  return float(1.0 / (double(subpaths) * (4.0 / 3.0) * kPi * r * r * r));
}

float PhotonMerging::surface_scale() const {
  const double r = double(surface_map.radius());
  return float(1.0 / (double(subpaths) * kPi * r * r));
}

namespace {

// Sums f(photon) over the photons near p, by the light group of each
// photon's light, and adds each group's sum times `scale` to the path as
// light after two events.
template <typename F>
void add_by_group(PathContext& ctx, const PhotonMap& map, const Vec3& p, const Rgb& scale,
                  const Rgb* diffuse_fraction, F&& f) {
  const Scene& scene = ctx.scene;
  thread_local std::vector<Rgb> by_group;
  by_group.assign(scene.group_names.size(), Rgb());
  bool any = false;
  map.for_each_near(p, [&](const Photon& ph) {
    const Rgb v = f(ph);
    if (v.is_black()) return;
    by_group[size_t(scene.light_group[ph.light])] += ph.weight * v;
    any = true;
  });
  if (!any) return;
  for (size_t g = 0; g < by_group.size(); ++g)
    if (!by_group[g].is_black()) ctx.add(by_group[g] * scale, 2, int(g), false, diffuse_fraction);
}

}  // namespace

void merge_medium_photons(PathContext& ctx, const Vec3& p, const HgPhase& phase, const Vec3& wo,
                          const PathState& path) {
  const PhotonMerging& pm = *ctx.options.photons;
  add_by_group(ctx, pm.map, p, path.throughput * pm.scale(), nullptr,
               [&](const Photon& ph) { return Rgb(phase.eval(wo, -ph.dir)); });
}

void merge_surface_photons(PathContext& ctx, const Vec3& p, const Vec3& n, const Bsdf& bsdf,
                           const Frame& frame, const Vec3& wo, const PathState& path) {
  const PhotonMerging& pm = *ctx.options.photons;
  const Rgb all_diffuse(1.f);
  add_by_group(ctx, pm.surface_map, p, path.throughput * pm.surface_scale(), &all_diffuse,
               [&](const Photon& ph) {
                 // Photons on this surface's plane, arriving on the viewer's side.
                 if (std::abs(dot(ph.n, n)) < 0.9f) return Rgb();
                 return bsdf_eval(bsdf, wo, frame.to_local(-ph.dir));
               });
}

float photon_radius(double photons, double volume) {
  if (!(photons > 0.0) || !(volume > 0.0)) return 0.f;
  const double k = 32.0 * std::pow(photons / 1e6, 0.4);
  return float(std::cbrt(3.0 * k * volume / (4.0 * kPi * photons)));
}

}  // namespace vesper
