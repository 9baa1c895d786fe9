#pragma once
// Light sampling helpers shared by surface and volume vertices.
#include <cmath>
#include <limits>

#include "renderer/integrator/volume_tracking.h"
#include "renderer/scene/scene.h"

namespace vesper {

// Fraction of light arriving along the shadow ray: 0 when a surface blocks
// it, the media's transmittance otherwise. The shadow ray (origin, dir, up
// to tmax) lives at the path's time.
template <bool kMedia>
Rgb shadow_transmittance(const Scene& scene, const Ray& shadow, Sampler& sampler, uint32_t& rays) {
  ++rays;
  if (scene.accel->occluded(shadow.origin, shadow.dir, shadow.tmax, shadow.time)) return Rgb{};
  if constexpr (kMedia) return estimate_transmittance(scene.media, shadow, shadow.tmax, sampler);
  return Rgb(1.f);
}

struct NoDeltaWeight {
  float operator()(size_t, const Vec3&) const { return 1.f; }
};
struct NoShaft {
  float operator()(size_t) const { return 0.f; }
};

struct DirectSample {
  Rgb value;    // contribution, before the path throughput
  Rgb diffuse;  // the diffuse lobe's share of value (surfaces)
  size_t light = 0;
  LightSampler::Sums selection;  // the light choice's sums at the point (MIS of the next ray)
};

// One light sample for the point at.p, chosen for `at` (light_sampler.h), at the path's `time`.
// `eval(wi)` returns {f * |cos| (or phase), its diffuse part, scattering pdf};
// `delta_weight(light, light point)` is the MIS weight of this strategy for delta (and sphere)
// lights: 1 unless equiangular sampling or light-vertex connections compete.
// `shaft(light)` is sun shafts' density over this strategy's, without the
// light choice and direction pdfs (sun_shaft.h): 0 where they do not compete.
template <bool kMedia, typename Eval, typename DeltaWeight = NoDeltaWeight,
          typename Shaft = NoShaft>
DirectSample sample_direct(const Scene& scene, const ShadingPoint& at, const Vec3& offset_normal,
                           float time, Sampler& sampler, uint32_t& rays, const Eval& eval,
                           const DeltaWeight& delta_weight = {}, const Shaft& shaft = {}) {
  DirectSample out;
  const Vec3& p = at.p;
  float pmf = 0.f, u_rest = 0.f;
  const size_t li = scene.light_sampler.sample(at, sampler.next1(), &pmf, &u_rest, &out.selection);
  const Vec2 u_light = sampler.next2();
  out.light = li;
  if (pmf <= 0.f) return out;
  const auto ls = scene.lights[li].sample(p, u_light);
  if (!ls || ls->pdf <= 0.f || ls->radiance.is_black()) return out;
  const auto [f, f_diffuse, scatter_pdf] = eval(ls->wi);
  if (f.is_black()) return out;
  Vec3 origin = p;
  Vec3 dir = ls->wi;
  float tmax = std::numeric_limits<float>::infinity();
  if (offset_normal.x != 0.f || offset_normal.y != 0.f || offset_normal.z != 0.f)
    origin =
        offset_ray_origin(p, dot(ls->wi, offset_normal) >= 0.f ? offset_normal : -offset_normal);
  if (!std::isinf(ls->distance)) {
    // Aim from the offset origin at the sampled light point itself, and stop
    // just short of it so the light's own surface does not occlude it.
    const Vec3 to_light = p + ls->wi * ls->distance - origin;
    const float dist = length(to_light);
    if (!(dist > 0.f)) return out;
    dir = to_light / dist;
    tmax = dist * (1.f - 1e-4f);
  }
  const Rgb tr = shadow_transmittance<kMedia>(scene, Ray{origin, dir, tmax, time}, sampler, rays);
  if (tr.is_black()) return out;
  const float light_pdf = pmf * ls->pdf;
  float w = ls->is_delta ? delta_weight(li, p + ls->wi * ls->distance)
                         : power_heuristic(light_pdf, scatter_pdf);
  // A sun that sun shafts also sampled: no other strategy competes for it,
  // so the three-way weight replaces delta_weight's.
  if (const float k = shaft(li); k > 0.f) {
    const float dir_pdf = ls->is_delta ? 1.f : ls->pdf;
    w = power_heuristic(pmf * dir_pdf, ls->is_delta ? 0.f : scatter_pdf, k * dir_pdf);
  }
  const Rgb light = ls->radiance * tr * (w / light_pdf);
  out.value = f * light;
  out.diffuse = f_diffuse * light;
  return out;
}

}  // namespace vesper
