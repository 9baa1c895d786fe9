#include "renderer/integrator/volume_tracking.h"

#include <cmath>
#include <vector>

namespace vesper {
namespace {

inline float sample_exponential(float u, float sigma) { return -std::log1p(-u) / sigma; }

std::vector<MajorantSpan>& scratch_spans() {
  thread_local std::vector<MajorantSpan> spans;
  return spans;
}

Rgb exp_rgb(const Rgb& x) { return {std::exp(x.r), std::exp(x.g), std::exp(x.b)}; }

}  // namespace

FreeFlight sample_free_flight(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                              const Ray& ray, Sampler& sampler, Rgb& throughput, Rgb& emitted) {
  const bool emissive = media.has_emission();
  for (const MajorantSpan& span : spans) {
    const float sigma_maj = span.sigma_maj;
    float t = span.t0;
    for (;;) {
      t += sample_exponential(sampler.next1(), sigma_maj);
      if (!(t < span.t1)) break;  // memoryless: continue in the next span
      const Vec3 p = ray.origin + ray.dir * t;
      const MediumCoefficients c = media.coefficients(p);
      // Collision-integral estimator with a grey majorant: every event's
      // weight is (its coefficient / sigma_maj) / (its probability).
      if (emissive && !c.emission.is_black()) emitted += throughput * c.emission / sigma_maj;
      const float p_absorb = c.sigma_a.average() / sigma_maj;
      const float p_scatter = c.sigma_s.average() / sigma_maj;
      const float p_null = std::max(0.f, 1.f - p_absorb - p_scatter);
      const float u = sampler.next1();
      if (u < p_absorb) return {FlightEvent::Absorbed, t, 0.f};
      if (u < p_absorb + p_scatter) {
        throughput *= c.sigma_s / (sigma_maj * p_scatter);
        return {FlightEvent::Scattered, t, media.pick_phase_g(p, sampler.next1())};
      }
      if (p_null <= 0.f) return {FlightEvent::Absorbed, t, 0.f};  // rounding: no null mass left
      const Rgb sigma_n = Rgb(sigma_maj) - c.sigma_a - c.sigma_s;
      throughput *= sigma_n / (sigma_maj * p_null);
    }
  }
  return {FlightEvent::Escaped, spans.empty() ? 0.f : spans.back().t1, 0.f};
}

namespace {
// Calls f(coefficients, t0, t1) for the parts of the analytic spans before t.
template <typename F>
void for_spans_before(const MediaSet& media, const std::vector<MajorantSpan>& spans, const Ray& ray,
                      float t, F&& f) {
  for (const MajorantSpan& s : spans) {
    if (s.t0 >= t) break;
    const float t1 = std::min(s.t1, t);
    const float mid = std::isinf(t1) ? s.t0 + 1.f : 0.5f * (s.t0 + t1);
    f(media.coefficients(ray.origin + ray.dir * mid), s.t0, t1);
  }
}
}  // namespace

Rgb analytic_transmittance(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                           const Ray& ray, float t) {
  Rgb optical;
  for_spans_before(media, spans, ray, t, [&](const MediumCoefficients& c, float a, float b) {
    optical += (c.sigma_a + c.sigma_s) * (b - a);
  });
  return exp_rgb(optical * -1.f);
}

float analytic_scatter_pdf(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                           const Ray& ray, float t) {
  double optical = 0;
  for_spans_before(media, spans, ray, t, [&](const MediumCoefficients& c, float a, float b) {
    optical += double((c.sigma_a + c.sigma_s).average()) * (b - a);
  });
  const MediumCoefficients here = media.coefficients(ray.origin + ray.dir * t);
  return float(here.sigma_s.average() * std::exp(-optical));
}

Rgb estimate_transmittance(const MediaSet& media, const Ray& ray, float tmax, Sampler& sampler) {
  auto& spans = scratch_spans();
  media.majorant_spans(ray, tmax, spans);
  Rgb tr(1.f);
  for (const MajorantSpan& span : spans) {
    if (span.analytic) {
      if (std::isinf(span.t1)) return Rgb{};
      const MediumCoefficients c =
          media.coefficients(ray.origin + ray.dir * (0.5f * (span.t0 + span.t1)));
      tr *= exp_rgb((c.sigma_a + c.sigma_s) * -(span.t1 - span.t0));
    } else {
      float t = span.t0;
      for (;;) {
        t += sample_exponential(sampler.next1(), span.sigma_maj);
        if (!(t < span.t1)) break;
        const MediumCoefficients c = media.coefficients(ray.origin + ray.dir * t);
        tr *= (Rgb(span.sigma_maj) - c.sigma_a - c.sigma_s) / span.sigma_maj;
        // Russian roulette once the estimate is small (unbiased).
        const float m = tr.max_component();
        if (m < 0.1f) {
          if (sampler.next1() < 0.5f) return Rgb{};
          tr *= 2.f;
        }
      }
    }
    if (tr.is_black()) return tr;
  }
  return tr;
}

}  // namespace vesper
