#include "renderer/integrator/volume_emission.h"

#include <cmath>

namespace vesper {
namespace {

// Points per emission voxel along the ray: one already resolves trilinear
// interpolation (piecewise smooth at the voxel scale).
constexpr float kPointsPerVoxel = 1.f;

Rgb integrate_grid(const GridMedium& g, const Ray& ray, float t_end,
                   const std::vector<ThroughputStep>& steps, float u) {
  const Vec3 o = map_at(g.emission_index_steps, g.render_to_emission_index, ray.time, ray.origin,
                        true),
             d = map_at(g.emission_index_steps, g.render_to_emission_index, ray.time, ray.dir,
                        false);
  const float voxels_per_t = length(d);
  if (!(voxels_per_t > 0.f)) return {};
  const float h = 1.f / (voxels_per_t * kPointsPerVoxel);  // lattice spacing in t
  Rgb sum;
  size_t step = 0;
  // The lattice starts where the ray enters the grid's box (the first
  // segment), so k counts voxels inside the grid: small, exact in a float
  // however far the ray's origin is.
  float anchor = -1.f;
  g.emission_majorants->walk(o, d, 0.f, t_end, [&](const MajorantSegment& s) {
    if (anchor < 0.f) anchor = s.t0;
    if (!(s.max_density > 0.f)) return true;
    // Lattice points t_k = anchor + (k + u) h with s.t0 <= t_k < s.t1: each
    // segment tests the same float t_k, so neighbouring segments share none.
    for (float k = std::max(0.f, std::floor((s.t0 - anchor) / h - u));; k += 1.f) {
      const float t = anchor + (k + u) * h;
      if (!(t < s.t1) || !(t < t_end)) break;
      if (t < s.t0) continue;
      while (step + 1 < steps.size() && steps[step + 1].t <= t) ++step;
      const float e = g.emission->sample(o + d * t);
      if (e > 0.f) sum += steps[step].throughput * e;
    }
    return true;
  });
  return sum * g.emission_coefficient * h;
}

}  // namespace

Rgb integrate_emission(const MediaSet& media, const Ray& ray, float t_end,
                       const std::vector<ThroughputStep>& steps, float u) {
  Rgb sum;
  for (const Medium& m : media.media())
    if (const auto* g = std::get_if<GridMedium>(&m); g && g->emission)
      sum += integrate_grid(*g, ray, t_end, steps, u);
  return sum;
}

}  // namespace vesper
