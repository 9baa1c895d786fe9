#include "renderer/integrator/light_vertex.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "renderer/integrator/equiangular_sampling.h"
#include "renderer/integrator/volume_tracking.h"
#include "renderer/lights/sphere_cone.h"
#include "renderer/math/constants.h"
#include "renderer/math/frame.h"

namespace vesper {
namespace {

bool connectable(const LightSampler& ls, size_t i) {
  const std::optional<LightBounds>& b = ls.bounds()[i];
  return b && (b->is_point() || b->sphere) && ls.powers()[i] > 0.f;
}

float sphere_radius(const LightBounds& b) { return 0.5f * (b.hi.x - b.lo.x); }

// The connectable lights' total power: light vertices pick by power.
float connectable_power(const LightSampler& ls) {
  float total = 0.f;
  for (size_t i = 0; i < ls.powers().size(); ++i)
    if (connectable(ls, i)) total += ls.powers()[i];
  return total;
}

// Emission directions are uniform in the light's cone (a point light's is
// the sphere: cos_cone = -1). A sphere light's ray then leaves a point of
// the hemisphere facing that direction, uniform in projected area.
float emission_pdf(const LightBounds& b) { return 1.f / (2.f * kPi * (1.f - b.cos_cone)); }

// The light-vertex strategy's density of (light point s, y) without the
// factor the path tracer's density shares: cos_s / |y - s|^2 for a sphere
// light (where next-event estimation picks s by solid angle), nothing for a
// delta light (whose 1 / |y - s|^2 the caller applies). `along` is
// distance_density from s to y.
float light_side_density(const LightBounds& b, float pmf, float along) {
  const float density = pmf * emission_pdf(b) * along;
  if (!b.sphere) return density;
  const float r = sphere_radius(b);
  return density / (kPi * r * r);
}

std::vector<MajorantSpan>& scratch_spans() {
  thread_local std::vector<MajorantSpan> spans;
  return spans;
}

// Densities of distance sampling along from -> to, deterministic (not
// estimated: volume_tracking.h's proxies, exact in homogeneous media): what
// the MIS weights need. In a medium, the density of scattering at `to`; on a
// surface, the probability of no collision before it.
float distance_density(const MediaSet& media, const Vec3& from, const Vec3& to, float time,
                       bool to_surface) {
  const Vec3 d = to - from;
  const float dist = length(d);
  if (!(dist > 0.f)) return 0.f;
  const Ray ray{from, d / dist, dist, time};
  auto& spans = scratch_spans();
  media.majorant_spans(ray, dist, spans);
  if (to_surface) return distance_sampling_proxy_survival(media, spans, ray, dist);
  return distance_sampling_proxy_pdf(media, spans, ray, dist);
}

// The density (per unit distance, light choice included) with which
// equiangular sampling on the ray from x through y picks y, over the media
// along the whole ray (light_vertex.h says why not up to a surface).
float equiangular_density(const Scene& scene, const Vec3& x, const Vec3& w_x, float dist,
                          size_t light, float time, bool clip_to_cone) {
  const Ray ray{x, w_x, std::numeric_limits<float>::infinity(), time};
  auto& spans = scratch_spans();
  scene.media.majorant_spans(ray, ray.tmax, spans);
  if (spans.empty()) return 0.f;
  return equiangular_pdf(scene.light_sampler.bounds()[light], ray, spans, dist, clip_to_cone) *
         scene.light_sampler.pmf_aimable(light);
}

struct Emission {
  Vec3 origin, dir;
  float weight = 0;  // per unit intensity: 1 / (the emission pdfs)
};

// Where and in which direction the light ray leaves light b; u_dir picks
// the direction, u_disk (sphere lights) the point. The weight is 1 / the
// emission pdfs per unit intensity: a sphere's radiance I / (pi r^2) times
// cos_s over the point's density cos_s / (pi r^2) leaves 1 / emission_pdf.
Emission sample_emission(const LightBounds& b, Vec2 u_dir, Vec2 u_disk) {
  Emission e;
  const float cos_t = 1.f - u_dir.x * (1.f - b.cos_cone);
  const float sin_t = std::sqrt(std::max(0.f, 1.f - cos_t * cos_t));
  const float phi = 2.f * kPi * u_dir.y;
  const Vec3 axis = length_squared(b.axis) > 0.f ? b.axis : Vec3(0.f, 0.f, 1.f);
  e.dir = normalize(
      Frame::from_normal(axis).to_world({sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t}));
  e.weight = 1.f / emission_pdf(b);
  e.origin = *b.aim();
  if (b.sphere) {
    const float rho = std::sqrt(u_disk.x), phi_d = 2.f * kPi * u_disk.y;
    const float dx = rho * std::cos(phi_d), dy = rho * std::sin(phi_d);
    const Frame f = Frame::from_normal(e.dir);
    e.origin +=
        f.to_world({dx, dy, std::sqrt(std::max(0.f, 1.f - dx * dx - dy * dy))}) * sphere_radius(b);
  }
  return e;
}

}  // namespace

bool light_vertices_pay_off(const Scene& scene) {
  if (scene.media.empty() || !(connectable_power(scene.light_sampler) > 0.f)) return false;
  const auto& media = scene.media.media();
  if (std::all_of(media.begin(), media.end(),
                  [](const Medium& m) { return std::holds_alternative<HomogeneousMedium>(m); }))
    return true;
  const LightSampler& ls = scene.light_sampler;
  for (size_t i = 0; i < ls.bounds().size(); ++i)
    if (connectable(ls, i) && !scene.media.coefficients(*ls.bounds()[i]->aim()).sigma_s.is_black())
      return true;
  return false;
}

std::optional<LightRayStart> sample_light_ray(const Scene& scene, Sampler& sampler) {
  const LightSampler& ls = scene.light_sampler;
  const float total = connectable_power(ls);
  const float u_light = sampler.next1();
  const Vec2 u_dir = sampler.next2();
  const Vec2 u_disk = sampler.next2();
  if (!(total > 0.f)) return std::nullopt;
  size_t li = ls.powers().size();
  float cum = 0.f;
  for (size_t i = 0; i < ls.powers().size(); ++i) {
    if (!connectable(ls, i)) continue;
    li = i;
    cum += ls.powers()[i];
    if (u_light * total < cum) break;
  }
  const Emission e = sample_emission(*ls.bounds()[li], u_dir, u_disk);
  const float pmf = ls.powers()[li] / total;
  return LightRayStart{li, e.origin, e.dir, e.weight / pmf};
}

Rgb light_ray_intensity(const Scene& scene, const LightRayStart& start, const Vec3& p) {
  const Vec3 from_centre = p - *scene.light_sampler.bounds()[start.light]->aim();
  if (!(length_squared(from_centre) > 0.f) || !(length_squared(p - start.origin) > 0.f)) return {};
  return scene.lights[start.light].intensity_toward(normalize(from_centre));
}

bool light_is_traced(const Scene& scene, size_t light) {
  return connectable(scene.light_sampler, light);
}

std::optional<LightVertex> trace_light_vertex(const Scene& scene, float time, Sampler& sampler,
                                              uint32_t& rays) {
  const std::optional<LightRayStart> e = sample_light_ray(scene, sampler);
  if (!e) return std::nullopt;
  const Ray ray{e->origin, e->dir, std::numeric_limits<float>::infinity(), time};
  const std::optional<SurfaceHit> hit = scene.accel->intersect(ray);
  ++rays;
  const float tmax = hit ? hit->t : std::numeric_limits<float>::infinity();
  auto& spans = scratch_spans();
  scene.media.majorant_spans(ray, tmax, spans);
  Rgb weight(1.f);
  const FreeFlight flight = sample_free_flight(scene.media, spans, ray, sampler, weight);
  if (flight.event == FlightEvent::Absorbed) return std::nullopt;
  LightVertex v;
  v.light = e->light;
  v.light_point = e->origin;
  if (flight.event == FlightEvent::Scattered) {
    v.p = ray.origin + ray.dir * flight.t;
    v.g = flight.g;
  } else {
    if (!hit || hit->light >= 0 || bsdf_is_delta(scene.materials[hit->material]))
      return std::nullopt;
    v.p = hit->p;
    v.n = hit->n;
    v.material = hit->material;
  }
  // A collision at distance 0 leaves no direction toward the light (its
  // phase would be NaN): an event of measure zero, dropped.
  const Rgb intensity = light_ray_intensity(scene, *e, v.p);
  if (intensity.is_black()) return std::nullopt;
  v.alpha = intensity * weight * e->weight;
  return v;
}

float light_vertex_weight(const Scene& scene, const Vec3& x, float pdf_x, const Vec3& y,
                          const Vec3& n_y, const Vec3& n_y_shading, size_t light,
                          const Vec3& light_point, float time, const PathStrategies& strategies) {
  const LightSampler& ls = scene.light_sampler;
  if (!connectable(ls, light) || !(pdf_x > 0.f)) return 0.f;
  const LightBounds& b = *ls.bounds()[light];
  const Vec3 s = b.sphere ? light_point : b.lo;  // a delta light's own position, unrounded
  const Vec3 from_light = y - s, from_x = y - x;
  const float r2 = length_squared(from_light), d2 = length_squared(from_x);
  if (!(r2 > 0.f) || !(d2 > 0.f)) return 0.f;
  const Vec3 w_light = from_light / std::sqrt(r2), w_x = from_x / std::sqrt(d2);
  // The light vertex cannot be at y: outside the cone, or (sphere lights)
  // from a point facing away from y. Checked before the densities, which
  // walk the media twice and weigh every light.
  if (b.cos_cone > -1.f && !(dot(w_light, b.axis) > b.cos_cone)) return 0.f;
  std::optional<SphereCone> cone;
  if (b.sphere) {
    const Vec3 centre = *b.aim();
    if (!(dot(s - centre, w_light) > 0.f)) return 0.f;
    cone = SphereCone::toward(y, centre, sphere_radius(b));
    if (!cone) return 0.f;
  }
  const bool surface = n_y.x != 0.f || n_y.y != 0.f || n_y.z != 0.f;
  const float pmf_light = ls.powers()[light] / connectable_power(ls);
  float p_light =
      light_side_density(b, pmf_light, distance_density(scene.media, s, y, time, surface));
  float p_path = distance_density(scene.media, x, y, time, surface) *
                 ls.pmf(ShadingPoint{y, n_y_shading}, light);
  if (!surface && strategies.equiangular) {
    const float p_eq = equiangular_density(scene, x, w_x, std::sqrt(d2), light, time,
                                           strategies.equiangular_in_cone);
    p_path = std::hypot(p_path, p_eq);
  }
  p_path *= pdf_x / d2;
  if (cone)
    p_path *= cone->pdf();
  else
    p_light /= r2;
  if (surface) {
    p_light *= std::abs(dot(n_y, w_light));
    p_path *= std::abs(dot(n_y, w_x));
  }
  if (!(p_light > 0.f)) return 0.f;
  if (!(p_path > 0.f)) return 1.f;
  const float ratio = p_path / p_light;
  return 1.f / (1.f + ratio * ratio);  // the power heuristic, overflow-safe
}

}  // namespace vesper
