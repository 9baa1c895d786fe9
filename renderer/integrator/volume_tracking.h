#pragma once
// Null-scattering estimators over a MediaSet: delta tracking to sample free
// flights, ratio tracking (or the analytic exponential where only homogeneous
// media are crossed) for transmittance on shadow rays.
#include "renderer/core/ray.h"
#include "renderer/media/media_set.h"
#include "renderer/sampling/sampler.h"

namespace vesper {

enum class FlightEvent { Escaped, Scattered, Absorbed };

struct FreeFlight {
  FlightEvent event = FlightEvent::Escaped;
  float t = 0;  // where it scattered
  float g = 0;  // phase function asymmetry of the medium that scattered
};

// Samples the next real collision along ray within [0, tmax). Updates the
// path throughput with the null-collision weights and adds volume emission
// (times throughput) to radiance.
// `spans` are media.majorant_spans(ray, tmax). Volume emission met on the
// way (times throughput) is added to `emitted`.
FreeFlight sample_free_flight(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                              const Ray& ray, Sampler& sampler, Rgb& throughput, Rgb& emitted);

// For rays whose spans are all analytic (homogeneous media only):
// transmittance from the ray origin to t, and the density with which
// sample_free_flight scatters at t (real collisions form a Poisson process
// of rate avg(sigma_t); a collision scatters with probability avg(sigma_s) / avg(sigma_t)).
Rgb analytic_transmittance(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                           const Ray& ray, float t);
float analytic_scatter_pdf(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                           const Ray& ray, float t);

// Unbiased transmittance estimate along ray over [0, tmax].
Rgb estimate_transmittance(const MediaSet& media, const Ray& ray, float tmax, Sampler& sampler);

}  // namespace vesper
