#pragma once
// Sun shafts: next-event estimation toward a sun from a distance sampled on
// every ray through homogeneous media, MIS'd with the distances delta
// tracking samples (where the path scatters) and with phase rays that
// escape toward the sun. What equiangular sampling is to point and spot
// lights: in thin fog most rays cross the medium without scattering (the
// night room's camera rays scatter one time in four), so a shaft through a
// window was sampled by a quarter of the rays; now every ray samples it.
//
// Distances have density sigma_t(t) exp(-tau(t)) / (1 - exp(-tau_total)):
// delta tracking's own collision density, conditioned on a collision within
// the ray's media (the sun's light is the same everywhere along the ray but
// for visibility and the transmittance toward it). Only rays whose spans are
// all homogeneous take part: there this density and delta tracking's are
// exact, so the MIS weights are. A path x(t) -> sun has three strategies,
// with densities (per unit t and, for a sun with an angle, solid angle):
//   a = p_d(t) pmf_nee(x, sun) p_dir   next-event estimation at a tracked vertex
//   b = p_d(t) p_phase                 a phase ray that escapes toward the sun
//   c = p_t(t) pmf_shaft(sun) p_dir    this strategy
// (b = 0 and p_dir = 1 for a sun without an angle); each takes its power
// heuristic share x^2 / (a^2 + b^2 + c^2).
#include <optional>
#include <vector>

#include "renderer/core/ray.h"
#include "renderer/math/rgb.h"
#include "renderer/media/media_set.h"
#include "renderer/sampling/sampler.h"
#include "renderer/scene/scene.h"

namespace vesper {

// The optical depth of `spans` (all analytic) at the RGB-average sigma_t
// delta tracking's proxy takes (volume_tracking.h); once per ray, for the
// functions below.
double shaft_optical_depth(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                           const Ray& ray);
// Distance sampling conditioned on a collision within `spans`, of optical
// depth `depth`; nullopt when it is 0.
std::optional<float> sample_shaft_distance(const MediaSet& media,
                                           const std::vector<MajorantSpan>& spans, const Ray& ray,
                                           double depth, float u);
// Its density at t (0 outside the spans).
float shaft_distance_pdf(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                         const Ray& ray, double depth, float t);

// True when sun shafts run on a ray with these spans: the scene has a sun
// and the spans are homogeneous (and there are some).
bool sun_shafts_apply(const Scene& scene, const std::vector<MajorantSpan>& spans);
// The probability that the shaft strategy picks light li (uniform over the
// suns; 0 for any other light).
float shaft_light_pmf(const Scene& scene, size_t li);

// p_t(t) / p_d(t) at distance t on a ray where sun shafts run: times
// shaft_light_pmf and p_dir, the shaft's density over delta tracking's,
// which is all the three strategies' weights need (each divides out p_d).
float shaft_to_tracking_ratio(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                              const Ray& ray, double depth, float t);

struct SunShaftSample {
  Rgb value;  // the weighted estimate, path throughput included
  size_t light = 0;
};

// One shaft sample on `ray` (spans: sun_shafts_apply holds; depth: their
// shaft_optical_depth), with the path throughput before the ray.
SunShaftSample sample_sun_shaft(const Scene& scene, const Ray& ray,
                                const std::vector<MajorantSpan>& spans, double depth,
                                const Rgb& throughput, Sampler& sampler, uint32_t& rays);

}  // namespace vesper
