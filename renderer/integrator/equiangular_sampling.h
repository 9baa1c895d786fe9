#pragma once
// Equiangular sampling as a strategy of the medium step: on every ray
// through media, a distance toward a light that is a single point, combined
// by MIS (power heuristic) with distance sampling followed by next-event
// estimation.
//
// Why this is unbiased in grid media too, where the density with which delta
// tracking scatters at t (avg sigma_s(t) times the transmittance) is unknown:
// MIS needs only weights w_e(t) + w_d(t) = 1 for every (ray, t, light), with
// each strategy's estimate unbiased for its weighted share. Both weights are
// the power heuristic of equiangular_pdf against the same deterministic
// distance_sampling_proxy_pdf (volume_tracking.h), so they are a partition of
// unity whatever that proxy is; the equiangular estimate's transmittance to t
// is an unbiased ratio-tracking estimate, independent of the rest of it.
// Where only homogeneous media are crossed the proxy is the exact density.
#include <optional>
#include <vector>

#include "renderer/core/ray.h"
#include "renderer/lights/light_bounds.h"
#include "renderer/media/media_set.h"
#include "renderer/sampling/sampler.h"
#include "renderer/scene/scene.h"

namespace vesper {

// Density (per unit t) with which sample_equiangular picks t toward the
// light of these bounds (LightSampler::bounds) over the spans' extent (with
// clip_to_cone: the part of it inside a spot light's cone); 0 for lights
// that are not a single point.
float equiangular_pdf(const std::optional<LightBounds>& light, const Ray& ray,
                      const std::vector<MajorantSpan>& spans, float t, bool clip_to_cone);

struct EquiangularSample {
  Rgb value;  // path throughput included; black when nothing was added
  size_t light = 0;
  float t = 0;         // the distance sampled
  Vec3 light_point{};  // the point sampled on the light
};

// One single-scattering estimate along `ray`: a light picked by the scene's
// light sampler, a distance toward it, the light seen from there through the
// media, MIS-weighted against distance sampling. Uses 3 sampler dimensions
// (and more for the shadow ray's transmittance).
EquiangularSample sample_equiangular(const Scene& scene, const Ray& ray,
                                     const std::vector<MajorantSpan>& spans, const Rgb& throughput,
                                     Sampler& sampler, uint32_t& rays, bool clip_to_cone);

}  // namespace vesper
