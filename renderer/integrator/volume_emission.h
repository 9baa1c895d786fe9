#pragma once
// Volume emission integrated on its own, independent of sigma_a and sigma_s:
// a medium that only emits (sigma_t = 0) gives delta tracking no collision
// at all, and a thin one gives a few collisions of weight emission / sigma_maj
// (the collision estimator's fireflies). Instead, the track-length estimator:
// with the free flight sampled by delta tracking, the emission integral
// ∫ T(t) e(t) dt over the path segment equals, in expectation, ∫ beta(t) e(t)
// dt over [0, t_end) — t_end the real collision (or the surface/escape) and
// beta the throughput, piecewise constant between null collisions. That
// integral is estimated by stratified points: a lattice one emission voxel
// apart from where the ray enters the grid, with one random offset, visited
// only in cells of the emission grid's own majorant grid that can emit
// (unbiased, as the offset is uniform; a constant emission is integrated
// exactly).
#include <vector>

#include "renderer/core/ray.h"
#include "renderer/media/media_set.h"

namespace vesper {

// The path throughput in effect from ray parameter t on (until the next step).
struct ThroughputStep {
  float t = 0;
  Rgb throughput;
};

// Emission along ray over [0, t_end) (t_end may be infinite), each point
// weighted by the throughput step it falls in; `steps` is non-empty, sorted
// by t, and starts at t = 0. `u` in [0, 1) is the lattice offset.
Rgb integrate_emission(const MediaSet& media, const Ray& ray, float t_end,
                       const std::vector<ThroughputStep>& steps, float u);

}  // namespace vesper
