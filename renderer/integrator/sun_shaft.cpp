#include "renderer/integrator/sun_shaft.h"

#include <cmath>
#include <limits>

#include "renderer/integrator/direct_lighting.h"
#include "renderer/integrator/volume_tracking.h"
#include "renderer/media/henyey_greenstein.h"

namespace vesper {
namespace {

// A homogeneous span's sigma_t (RGB average), as distance_sampling_proxy_pdf
// takes it: at the span's middle.
float span_sigma_t(const MediaSet& media, const MajorantSpan& s, const Ray& ray) {
  const float mid = std::isinf(s.t1) ? s.t0 + 1.f : 0.5f * (s.t0 + s.t1);
  const MediumCoefficients c = media.coefficients(ray.origin + ray.dir * mid, ray.time);
  return (c.sigma_a + c.sigma_s).average();
}

double span_depth(float sigma_t, const MajorantSpan& s) {
  return std::isinf(s.t1) ? std::numeric_limits<double>::infinity()
                          : double(sigma_t) * (s.t1 - s.t0);
}

size_t sun_count(const Scene& scene) { return scene.suns.size(); }

}  // namespace

std::optional<float> sample_shaft_distance(const MediaSet& media,
                                           const std::vector<MajorantSpan>& spans, const Ray& ray,
                                           float u) {
  double total = 0;
  for (const MajorantSpan& s : spans) total += span_depth(span_sigma_t(media, s, ray), s);
  if (!(total > 0)) return std::nullopt;
  // The optical depth of the collision, from the exponential's CDF
  // restricted to [0, total).
  const double target = -std::log1p(-double(u) * -std::expm1(-total));
  double tau = 0;
  for (const MajorantSpan& s : spans) {
    const float sigma = span_sigma_t(media, s, ray);
    const double depth = span_depth(sigma, s);
    if (target < tau + depth && sigma > 0.f)
      return std::fmin(std::fmax(s.t0 + float((target - tau) / sigma), s.t0), s.t1);
    tau += depth;
  }
  return std::nullopt;  // rounding past the last span
}

float shaft_distance_pdf(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                         const Ray& ray, float t) {
  double total = 0, tau_t = -1;
  float sigma_at_t = 0.f;
  for (const MajorantSpan& s : spans) {
    const float sigma = span_sigma_t(media, s, ray);
    if (tau_t < 0 && t >= s.t0 && t <= s.t1) {
      tau_t = total + double(sigma) * (t - s.t0);
      sigma_at_t = sigma;
    }
    total += span_depth(sigma, s);
  }
  if (tau_t < 0 || !(total > 0)) return 0.f;
  return float(sigma_at_t * std::exp(-tau_t) / -std::expm1(-total));
}

bool sun_shafts_apply(const Scene& scene, const std::vector<MajorantSpan>& spans) {
  if (spans.empty() || sun_count(scene) == 0) return false;
  for (const MajorantSpan& s : spans)
    if (!s.analytic) return false;
  return true;
}

float shaft_light_pmf(const Scene& scene, size_t li) {
  if (!scene.lights[li].is_sun()) return 0.f;
  return 1.f / float(sun_count(scene));
}

float shaft_to_tracking_ratio(const Scene& scene, const std::vector<MajorantSpan>& spans,
                              const Ray& ray, float t) {
  if (!sun_shafts_apply(scene, spans)) return 0.f;
  const float p_d = distance_sampling_proxy_pdf(scene.media, spans, ray, t);
  if (!(p_d > 0.f)) return 0.f;
  return shaft_distance_pdf(scene.media, spans, ray, t) / p_d;
}

SunShaftSample sample_sun_shaft(const Scene& scene, const Ray& ray,
                                const std::vector<MajorantSpan>& spans, const Rgb& throughput,
                                Sampler& sampler, uint32_t& rays) {
  SunShaftSample out;
  // Only the numbers this scene needs: each slot taken here moves every
  // later choice of the path off the low-discrepancy slots (sampler.h),
  // which measurably cost more noise than the shaft saved with a delta sun.
  const size_t n = sun_count(scene);
  if (n == 0) return out;
  const float u_t = sampler.next1();
  const float u_pick = n > 1 ? sampler.next1() : 0.f;
  const float u_g = scene.media.media().size() > 1 ? sampler.next1() : 0.5f;
  out.light = scene.suns[std::min(n - 1, size_t(u_pick * float(n)))];
  const std::optional<float> t = sample_shaft_distance(scene.media, spans, ray, u_t);
  if (!t) return out;
  const float p_t = shaft_distance_pdf(scene.media, spans, ray, *t);
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
  // The three strategies' densities (sun_shaft.h).
  const float dir_pdf = ls->is_delta ? 1.f : ls->pdf;
  const float p_d = distance_sampling_proxy_pdf(scene.media, spans, ray, *t);
  const float a = p_d * scene.light_sampler.pmf(ShadingPoint{x, Vec3(0.f)}, out.light) * dir_pdf;
  const float b = ls->is_delta ? 0.f : p_d * phase.pdf(-ray.dir, ls->wi);
  const float cs = p_t * (1.f / float(n)) * dir_pdf;
  const float w = 1.f / (1.f + (a / cs) * (a / cs) + (b / cs) * (b / cs));
  out.value = throughput * tr * c.sigma_s * ls->radiance * tr_sun * (f * w / cs);
  return out;
}

}  // namespace vesper
