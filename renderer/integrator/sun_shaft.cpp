#include "renderer/integrator/sun_shaft.h"

#include <cmath>
#include <limits>

#include "renderer/integrator/direct_lighting.h"
#include "renderer/integrator/volume_tracking.h"
#include "renderer/media/henyey_greenstein.h"

namespace vesper {
namespace {

// A homogeneous span's sigma_t (RGB average), as distance_sampling_proxy_pdf
// takes it.
float span_sigma_t(const MediaSet& media, const MajorantSpan& s, const Ray& ray) {
  const MediumCoefficients c = analytic_coefficients(media, s, ray);
  return (c.sigma_a + c.sigma_s).average();
}

double span_depth(float sigma_t, const MajorantSpan& s) {
  return std::isinf(s.t1) ? std::numeric_limits<double>::infinity()
                          : double(sigma_t) * (s.t1 - s.t0);
}

}  // namespace

double shaft_optical_depth(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                           const Ray& ray) {
  double depth = 0;
  for (const MajorantSpan& s : spans) depth += span_depth(span_sigma_t(media, s, ray), s);
  return depth;
}

std::optional<float> sample_shaft_distance(const MediaSet& media,
                                           const std::vector<MajorantSpan>& spans, const Ray& ray,
                                           double depth, float u) {
  if (!(depth > 0)) return std::nullopt;
  // The optical depth of the collision, from the exponential's CDF
  // restricted to [0, depth).
  const double target = -std::log1p(-double(u) * -std::expm1(-depth));
  double tau = 0;
  for (const MajorantSpan& s : spans) {
    const float sigma = span_sigma_t(media, s, ray);
    const double span = span_depth(sigma, s);
    if (target < tau + span && sigma > 0.f)
      return std::fmin(std::fmax(s.t0 + float((target - tau) / sigma), s.t0), s.t1);
    tau += span;
  }
  return std::nullopt;  // rounding past the last span
}

float shaft_distance_pdf(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                         const Ray& ray, double depth, float t) {
  if (!(depth > 0)) return 0.f;
  double tau = 0;
  for (const MajorantSpan& s : spans) {
    if (t < s.t0) break;
    const float sigma = span_sigma_t(media, s, ray);
    if (t <= s.t1)
      return float(sigma * std::exp(-(tau + double(sigma) * (t - s.t0))) / -std::expm1(-depth));
    tau += span_depth(sigma, s);
  }
  return 0.f;
}

bool sun_shafts_apply(const Scene& scene, const std::vector<MajorantSpan>& spans) {
  return !spans.empty() && !scene.suns.empty() && !crosses_grid(spans);
}

float shaft_light_pmf(const Scene& scene, size_t li) {
  return scene.lights[li].is_sun() ? 1.f / float(scene.suns.size()) : 0.f;
}

float shaft_to_tracking_ratio(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                              const Ray& ray, double depth, float t) {
  const float p_d = distance_sampling_proxy_pdf(media, spans, ray, t);
  return p_d > 0.f ? shaft_distance_pdf(media, spans, ray, depth, t) / p_d : 0.f;
}

SunShaftSample sample_sun_shaft(const Scene& scene, const Ray& ray,
                                const std::vector<MajorantSpan>& spans, double depth,
                                const Rgb& throughput, Sampler& sampler, uint32_t& rays) {
  SunShaftSample out;
  // Only the numbers this scene needs: each slot taken here moves every
  // later choice of the path off the low-discrepancy slots (sampler.h),
  // which measurably cost more noise than the shaft saved with a delta sun.
  const size_t n = scene.suns.size();
  if (n == 0) return out;
  const float u_t = sampler.next1();
  const float u_pick = n > 1 ? sampler.next1() : 0.f;
  const float u_g = scene.media.media().size() > 1 ? sampler.next1() : 0.5f;
  out.light = scene.suns[std::min(n - 1, size_t(u_pick * float(n)))];
  const std::optional<float> t = sample_shaft_distance(scene.media, spans, ray, depth, u_t);
  if (!t) return out;
  const float p_t = shaft_distance_pdf(scene.media, spans, ray, depth, *t);
  const Vec3 x = ray.origin + ray.dir * *t;
  const MediumCoefficients c = scene.media.coefficients(x, ray.time);
  const Light& sun = scene.lights[out.light];
  const auto ls = sun.sample(x, sun.is_delta_sun() ? Vec2{} : sampler.next2());
  if (!(p_t > 0.f) || c.sigma_s.is_black() || !ls || !(ls->pdf > 0.f) || ls->radiance.is_black())
    return out;
  const HgPhase phase{scene.media.pick_phase_g(x, u_g, ray.time)};
  const float f = phase.eval(-ray.dir, ls->wi);
  if (!(f > 0.f)) return out;
  const Rgb tr = estimate_transmittance_to(scene.media, spans, ray, *t, sampler);
  const Rgb tr_sun = shadow_transmittance<true>(
      scene, Ray{x, ls->wi, std::numeric_limits<float>::infinity(), ray.time}, sampler, rays);
  if (tr.is_black() || tr_sun.is_black()) return out;
  // The three strategies' densities over delta tracking's (sun_shaft.h),
  // as next-event estimation and the escaping phase ray weigh them.
  const float dir_pdf = ls->is_delta ? 1.f : ls->pdf;
  const float pmf_shaft = 1.f / float(n);
  // shaft_to_tracking_ratio, with p_t already at hand.
  const float p_d = distance_sampling_proxy_pdf(scene.media, spans, ray, *t);
  const float shaft = (p_d > 0.f ? p_t / p_d : 0.f) * pmf_shaft;
  const float w = power_heuristic(
      shaft * dir_pdf, scene.light_sampler.pmf(ShadingPoint{x, Vec3(0.f)}, out.light) * dir_pdf,
      ls->is_delta ? 0.f : phase.pdf(-ray.dir, ls->wi));
  out.value =
      throughput * tr * c.sigma_s * ls->radiance * tr_sun * (f * w / (p_t * pmf_shaft * dir_pdf));
  return out;
}

}  // namespace vesper
