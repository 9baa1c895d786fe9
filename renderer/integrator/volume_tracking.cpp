#include "renderer/integrator/volume_tracking.h"

#include <cmath>
#include <vector>

namespace vesper {
namespace {

std::vector<MajorantSpan>& scratch_spans() {
  thread_local std::vector<MajorantSpan> spans;
  return spans;
}

Rgb exp_rgb(const Rgb& x) { return {std::exp(x.r), std::exp(x.g), std::exp(x.b)}; }

}  // namespace

FreeFlight sample_free_flight(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                              const Ray& ray, Sampler& sampler, Rgb& throughput,
                              std::vector<ThroughputStep>* steps) {
  if (steps) steps->push_back({0.f, throughput});
  FreeFlight flight;
  for (const MajorantSpan& span : spans) {
    const float sigma_maj = span.sigma_maj;
    // Collision-integral estimator with a grey majorant: every event's
    // weight is (its coefficient / sigma_maj) / (its probability).
    auto at_collision = [&](float t, const Vec3& p, const MediumCoefficients& c) {
      const float p_absorb = c.sigma_a.average() / sigma_maj;
      const float p_scatter = c.sigma_s.average() / sigma_maj;
      const float p_null = std::max(0.f, 1.f - p_absorb - p_scatter);
      const float u = sampler.next1();
      if (u < p_absorb) {
        flight = {FlightEvent::Absorbed, t, 0.f};
        return false;
      }
      if (u < p_absorb + p_scatter) {
        throughput *= c.sigma_s / (sigma_maj * p_scatter);
        flight = {FlightEvent::Scattered, t, media.pick_phase_g(p, sampler.next1(), ray.time)};
        return false;
      }
      if (p_null <= 0.f) {  // rounding: no null mass left
        flight = {FlightEvent::Absorbed, t, 0.f};
        return false;
      }
      const Rgb sigma_n = Rgb(sigma_maj) - c.sigma_a - c.sigma_s;
      const Rgb weight = sigma_n / (sigma_maj * p_null);
      if (!(weight == Rgb(1.f))) {  // grey media: always 1, no step
        throughput *= weight;
        if (steps) steps->push_back({t, throughput});
      }
      return true;
    };
    if (!for_each_tentative_collision(media, span, ray, sampler, at_collision)) return flight;
  }
  return {FlightEvent::Escaped, spans.empty() ? 0.f : spans.back().t1, 0.f};
}

MediumCoefficients analytic_coefficients(const MediaSet& media, const MajorantSpan& s,
                                         const Ray& ray) {
  const float mid = std::isinf(s.t1) ? s.t0 + 1.f : 0.5f * (s.t0 + s.t1);
  return media.coefficients(ray.origin + ray.dir * mid, ray.time);
}

namespace {
// Calls f(span) for the spans before t, the last one clipped at t.
template <typename F>
void for_spans_before(const std::vector<MajorantSpan>& spans, float t, F&& f) {
  for (MajorantSpan s : spans) {
    if (s.t0 >= t) break;
    s.t1 = std::min(s.t1, t);
    f(s);
  }
}

// Ratio tracking across one span, multiplying tr by each null collision's
// weight. Returns false when Russian roulette ended it (tr is then 0).
bool ratio_track_span(const MediaSet& media, const MajorantSpan& span, const Ray& ray,
                      Sampler& sampler, Rgb& tr) {
  return for_each_tentative_collision(
      media, span, ray, sampler, [&](float, const Vec3&, const MediumCoefficients& c) {
        tr *= (Rgb(span.sigma_maj) - c.sigma_a - c.sigma_s) / span.sigma_maj;
        // Russian roulette once the estimate is small (unbiased).
        if (tr.max_component() < 0.1f) {
          if (sampler.next1() < 0.5f) return false;
          tr *= 2.f;
        }
        return true;
      });
}
}  // namespace

Rgb estimate_transmittance_to(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                              const Ray& ray, float t, Sampler& sampler) {
  // The analytic spans' optical depths are summed and exponentiated once
  // (not span by span): homogeneous media then give the very bits the
  // equiangular estimate had before it ran in grids.
  Rgb optical, ratio(1.f);
  bool ended = false;
  for_spans_before(spans, t, [&](const MajorantSpan& s) {
    if (ended) return;
    if (s.analytic) {
      const MediumCoefficients c = analytic_coefficients(media, s, ray);
      optical += (c.sigma_a + c.sigma_s) * (s.t1 - s.t0);
    } else {
      ended = !ratio_track_span(media, s, ray, sampler, ratio);
    }
  });
  if (ended) return Rgb{};
  return ratio * exp_rgb(optical * -1.f);
}

float distance_sampling_proxy_survival(const MediaSet& media,
                                       const std::vector<MajorantSpan>& spans, const Ray& ray,
                                       float t) {
  double optical = 0;
  for_spans_before(spans, t, [&](const MajorantSpan& s) {
    float sigma_t = s.sigma_maj;
    if (s.analytic) {
      const MediumCoefficients c = analytic_coefficients(media, s, ray);
      sigma_t = (c.sigma_a + c.sigma_s).average();
    }
    optical += double(sigma_t) * (s.t1 - s.t0);
  });
  return float(std::exp(-optical));
}

float distance_sampling_proxy_pdf(const MediaSet& media, const std::vector<MajorantSpan>& spans,
                                  const Ray& ray, float t) {
  const MediumCoefficients here = media.coefficients(ray.origin + ray.dir * t, ray.time);
  return here.sigma_s.average() * distance_sampling_proxy_survival(media, spans, ray, t);
}

Rgb estimate_transmittance(const MediaSet& media, const Ray& ray, float tmax, Sampler& sampler) {
  auto& spans = scratch_spans();
  media.majorant_spans(ray, tmax, spans);
  Rgb tr(1.f);
  for (const MajorantSpan& span : spans) {
    if (span.analytic) {
      if (std::isinf(span.t1)) return Rgb{};
      const MediumCoefficients c = analytic_coefficients(media, span, ray);
      tr *= exp_rgb((c.sigma_a + c.sigma_s) * -(span.t1 - span.t0));
    } else if (!ratio_track_span(media, span, ray, sampler, tr)) {
      return Rgb{};
    }
    if (tr.is_black()) return tr;
  }
  return tr;
}

}  // namespace vesper
