#include "renderer/integrator/equiangular_sampling.h"

#include <optional>

#include "renderer/integrator/cone_interval.h"
#include "renderer/integrator/direct_lighting.h"
#include "renderer/integrator/equiangular.h"
#include "renderer/integrator/equiangular_reach.h"
#include "renderer/integrator/volume_tracking.h"
#include "renderer/media/henyey_greenstein.h"

namespace vesper {
namespace {

// The segment from the first span's start to the last span's end, seen from
// the light's aim point (point and spot lights, with or without a radius),
// clipped to a spot light's cone (cone_interval.h). The bounds are the
// light sampler's, built once: Light::bounds() builds them on every call,
// and this runs several times at every medium vertex (fog-shafts rendered
// 12 % slower that way).
std::optional<EquiangularSegment> segment_toward(const std::optional<LightBounds>& b,
                                                 const Ray& ray,
                                                 const std::vector<MajorantSpan>& spans,
                                                 bool clip_to_cone) {
  const std::optional<Vec3> aim = b ? b->aim() : std::nullopt;
  if (!aim) return std::nullopt;
  TInterval lit{spans.front().t0, spans.back().t1};
  if (clip_to_cone && !b->cosine) {
    const auto in_cone =
        cone_interval(ray.origin, ray.dir, *aim, b->axis, b->cos_cone, lit.t0, lit.t1);
    if (!in_cone) return std::nullopt;
    lit = *in_cone;
  }
  return EquiangularSegment::make(ray.origin, ray.dir, *aim, lit.t0, lit.t1);
}

// segment_toward over the spans within depth, for lights within reach of
// the ray (equiangular_reach.h).
std::optional<EquiangularSegment> eligible_segment(const std::optional<LightBounds>& light,
                                                   const Ray& ray,
                                                   const std::vector<MajorantSpan>& spans,
                                                   bool clip_to_cone) {
  // Homogeneous rays: every span, no reach rule (and no copy: this runs for
  // every medium vertex and every MIS weight).
  if (!crosses_grid(spans)) return segment_toward(light, ray, spans, clip_to_cone);
  thread_local std::vector<MajorantSpan> near;
  spans_within_depth(spans, near);
  auto seg = segment_toward(light, ray, near, clip_to_cone);
  if (seg && !light_within_reach(*seg, near)) return std::nullopt;
  return seg;
}

}  // namespace

float equiangular_pdf(const std::optional<LightBounds>& light, const Ray& ray,
                      const std::vector<MajorantSpan>& spans, float t, bool clip_to_cone) {
  const auto seg = eligible_segment(light, ray, spans, clip_to_cone);
  return seg ? seg->pdf(t) : 0.f;
}

EquiangularSample sample_equiangular(const Scene& scene, const Ray& ray,
                                     const std::vector<MajorantSpan>& spans, const Rgb& throughput,
                                     Sampler& sampler, uint32_t& rays, bool clip_to_cone) {
  EquiangularSample out;
  float pmf = 0.f, u_rest = 0.f;
  const float u_pick = sampler.next1();
  const Vec2 u_eq = sampler.next2();
  if (!scene.light_sampler.has_aimable()) return out;
  const size_t li = scene.light_sampler.sample_aimable(u_pick, &pmf, &u_rest);
  out.light = li;
  const Light& light = scene.lights[li];
  const auto seg = eligible_segment(scene.light_sampler.bounds()[li], ray, spans, clip_to_cone);
  if (!seg || !(pmf > 0.f)) return out;
  const float t = seg->sample(u_eq.x);
  out.t = t;
  const float pdf_e = seg->pdf(t);
  const Vec3 x = ray.origin + ray.dir * t;
  const MediumCoefficients c = scene.media.coefficients(x, ray.time);
  // A sphere light samples a point on itself (the MIS weights below are over
  // the distance only, so any unbiased light sample fits); a point light
  // needs no numbers, and takes none, as before radii existed.
  const Vec2 u_light = scene.light_sampler.bounds()[li]->is_point() ? Vec2{} : sampler.next2();
  const auto ls = light.sample(x, u_light);
  if (!(pdf_e > 0.f) || c.sigma_s.is_black() || !ls || ls->radiance.is_black()) return out;
  out.light_point = x + ls->wi * ls->distance;
  // The transmittance to t before the shadow ray: in dense grid media ratio
  // tracking often ends early (Russian roulette), and then no ray is needed.
  const Rgb tr = estimate_transmittance_to(scene.media, spans, ray, t, sampler);
  if (tr.is_black()) return out;
  const HgPhase phase{scene.media.pick_phase_g(x, u_eq.y, ray.time)};
  const float f = phase.eval(-ray.dir, ls->wi);
  const Rgb tr_light = shadow_transmittance<true>(
      scene, Ray{x, ls->wi, ls->distance * (1.f - 1e-4f), ray.time}, sampler, rays);
  if (tr_light.is_black()) return out;
  const float pdf_a = distance_sampling_proxy_pdf(scene.media, spans, ray, t);
  const float w = power_heuristic(pdf_e, pdf_a);
  out.value = throughput * tr * c.sigma_s * ls->radiance * tr_light * (f * w / (pdf_e * pmf));
  return out;
}

}  // namespace vesper
