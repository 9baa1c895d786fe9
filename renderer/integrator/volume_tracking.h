#pragma once
// Null-scattering estimators over a MediaSet: delta tracking to sample free
// flights, ratio tracking (or the analytic exponential where only homogeneous
// media are crossed) for transmittance on shadow rays. Both walk the same
// tentative collisions (for_each_tentative_collision).
#include <cmath>
#include <vector>

#include "renderer/core/ray.h"
#include "renderer/integrator/volume_emission.h"
#include "renderer/media/media_set.h"
#include "renderer/sampling/sampler.h"

namespace vesper {

inline float sample_exponential(float u, float sigma) { return -std::log1p(-u) / sigma; }

// The tentative collisions of null-scattering tracking along one majorant
// span (after pbrt-v4's SampleT_maj): exponential steps of rate
// span.sigma_maj from span.t0, each taking one sampler dimension. At every
// t < span.t1, at_collision(t, position, coefficients there) says whether
// to go on (a null collision) or to stop. Returns false when it stopped.
template <typename AtCollision>
bool for_each_tentative_collision(const MediaSet& media, const MajorantSpan& span, const Ray& ray,
                                  Sampler& sampler, AtCollision&& at_collision) {
  float t = span.t0;
  for (;;) {
    t += sample_exponential(sampler.next1(), span.sigma_maj);
    if (!(t < span.t1)) return true;  // memoryless: go on in the next span
    const Vec3 p = ray.origin + ray.dir * t;
    if (!at_collision(t, p, media.coefficients(p, ray.time))) return false;
  }
}

enum class FlightEvent { Escaped, Scattered, Absorbed };

struct FreeFlight {
  FlightEvent event = FlightEvent::Escaped;
  float t = 0;  // where it scattered
  float g = 0;  // phase function asymmetry of the medium that scattered
};

// Samples the next real collision along ray within [0, tmax) by delta
// tracking; `spans` are media.majorant_spans(ray, tmax). Updates the path
// throughput with the null-collision weights. With `steps` (for volume
// emission, volume_emission.h), the throughput before the flight and after
// each null collision is appended to it (not the real collision's weight).
FreeFlight sample_free_flight(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                              const Ray& ray, Sampler& sampler, Rgb& throughput,
                              std::vector<ThroughputStep>* steps = nullptr);

// Unbiased transmittance estimate from the ray origin to t, over `spans`
// (media.majorant_spans of the ray): the analytic spans exactly, the others
// by ratio tracking (the only sampler dimensions it takes). Over analytic
// spans only, it is the exact exp(-optical depth).
Rgb estimate_transmittance_to(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                              const Ray& ray, float t, Sampler& sampler);

// The coefficients of an analytic span (constant along it), read at its
// middle (a unit in, for a span without end).
MediumCoefficients analytic_coefficients(const MediaSet& media, const MajorantSpan& s,
                                         const Ray& ray);

// A deterministic stand-in for the density (per unit t) with which
// sample_free_flight scatters at t: avg(sigma_s(t)) * exp(-sum over the spans
// before t of avg(sigma_t) * length (analytic) or sigma_maj * length (grid)).
// Exact where only homogeneous media are crossed (real collisions form a
// Poisson process of rate avg(sigma_t), each scattering with probability
// avg(sigma_s) / avg(sigma_t)); elsewhere the true density, avg(sigma_s(t))
// times the unknown transmittance, has no closed form. MIS weights only need
// to be deterministic functions of t (equiangular_sampling.h), so this serves.
float distance_sampling_proxy_pdf(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                                  const Ray& ray, float t);
// Its exp(-...) factor alone: the stand-in for the probability that
// sample_free_flight passes t without a real collision (a surface at t).
float distance_sampling_proxy_survival(const MediaSet& media,
                                       const std::vector<MajorantSpan>& spans, const Ray& ray,
                                       float t);

// Unbiased transmittance estimate along ray over [0, tmax].
Rgb estimate_transmittance(const MediaSet& media, const Ray& ray, float tmax, Sampler& sampler);

}  // namespace vesper
