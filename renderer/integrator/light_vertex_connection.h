#pragma once
// Connecting a scattering vertex of the camera path to the sample's light
// vertex (light_vertex.h).
#include <cmath>
#include <tuple>

#include "renderer/integrator/direct_lighting.h"
#include "renderer/integrator/light_vertex.h"
#include "renderer/math/frame.h"
#include "renderer/media/henyey_greenstein.h"

namespace vesper {

// The connection's contribution (path throughput excluded, MIS weight
// included) from x, whose ray origin leaves along offset_normal (zero in a
// medium). `eval(wi)` returns {f * |cos| (or the phase), scattering pdf} at x.
template <typename Eval>
Rgb connect_light_vertex(const Scene& scene, const LightVertex& lv, const Vec3& x,
                         const Vec3& offset_normal, float time, Sampler& sampler, uint32_t& rays,
                         const PathStrategies& strategies, const Eval& eval) {
  const Vec3 to_y = lv.p - x;
  const float d2 = length_squared(to_y);
  if (!(d2 > 0.f)) return {};
  const Vec3 dir = to_y / std::sqrt(d2);
  const auto [f_x, pdf_x] = eval(dir);
  if (f_x.is_black()) return {};
  // No direction toward the light from a vertex on it (trace_light_vertex
  // makes none; a NaN phase here would poison the pixel).
  if (!(length_squared(lv.light_point - lv.p) > 0.f)) return {};
  const Vec3 to_light = normalize(lv.light_point - lv.p);
  Rgb f_y;
  float cos_y = 1.f;
  Vec3 n_y_shading{};
  if (lv.on_surface()) {
    const Bsdf& bsdf = scene.materials[lv.material];
    // Shaded as the path tracer would at y, seen from x (scatter_at_surface):
    // its light choice there is part of the MIS weight.
    const Vec3 n = bsdf_shading_normal(bsdf, lv.n, -dir);
    const Frame frame = Frame::from_normal(n);
    f_y = bsdf_eval(bsdf, frame.to_local(-dir), frame.to_local(to_light));
    cos_y = std::abs(dot(lv.n, dir));
    n_y_shading = bsdf_transmits(bsdf) ? Vec3(0.f) : n;
  } else {
    f_y = Rgb(HgPhase{lv.g}.eval(-dir, to_light));
  }
  if (f_y.is_black()) return {};
  const bool offset = offset_normal.x != 0.f || offset_normal.y != 0.f || offset_normal.z != 0.f;
  const Vec3 origin =
      offset ? offset_ray_origin(x, dot(dir, offset_normal) >= 0.f ? offset_normal : -offset_normal)
             : x;
  const Vec3 span = lv.p - origin;
  const float dist = length(span);
  if (!(dist > 0.f)) return {};
  const Rgb tr = shadow_transmittance<true>(
      scene, Ray{origin, span / dist, dist * (1.f - 1e-4f), time}, sampler, rays);
  if (tr.is_black()) return {};
  const float u = light_vertex_weight(scene, x, pdf_x, lv.p, lv.n, n_y_shading, lv.light,
                                      lv.light_point, time, strategies);
  return f_x * tr * f_y * lv.alpha * (cos_y * u / d2);
}

}  // namespace vesper
