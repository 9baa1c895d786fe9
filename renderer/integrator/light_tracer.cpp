#include "renderer/integrator/light_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <variant>

#include "renderer/integrator/direct_lighting.h"
#include "renderer/integrator/light_vertex.h"
#include "renderer/integrator/volume_tracking.h"
#include "renderer/math/frame.h"
#include "renderer/media/henyey_greenstein.h"
#include "renderer/sampling/pixel_filter.h"

namespace vesper {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// The connection from vertex y (light arriving along `dir_in`, with `flux`
// the subpath's weight there) to the pinhole camera. `scatter(to_cam)` is
// the phase function, or the BSDF times |cos| at a surface (and the shadow
// ray's origin, offset off the surface).
template <typename Scatter>
void connect_to_camera(const Scene& scene, const Vec3& y, const Rgb& flux, size_t light,
                       FirstEvent kind, Sampler& sampler, uint32_t& rays,
                       std::vector<CameraSplat>& out, const Scatter& scatter) {
  const Camera& cam = scene.camera;
  const Vec3 v = y - cam.position;
  const float z = dot(v, cam.forward);
  if (!(z > 0.f)) return;
  const float fx = (dot(v, cam.right) / (z * cam.tan_half_x) + 1.f) * 0.5f * float(cam.width);
  const float fy = (1.f - dot(v, cam.up) / (z * cam.tan_half_y)) * 0.5f * float(cam.height);
  // The filter reaches kGaussianRadius beyond the raster's edge at most.
  const float margin = scene.film.filter == FilterType::Box ? 0.f : kGaussianRadius;
  if (!(fx > -margin && fy > -margin && fx < float(cam.width) + margin &&
        fy < float(cam.height) + margin))
    return;
  const float d2 = length_squared(v);
  const float d = std::sqrt(d2);
  const Vec3 to_cam = -v / d;
  const auto [f, origin] = scatter(to_cam);
  if (f.is_black()) return;
  const Vec3 span = cam.position - origin;
  const float dist = length(span);
  if (!(dist > 0.f)) return;
  const Rgb tr = shadow_transmittance<true>(
      scene, Ray{origin, span / dist, dist * (1.f - 1e-4f), 0.f}, sampler, rays);
  if (tr.is_black()) return;
  // The pinhole's importance per unit solid angle, per raster pixel: the
  // raster area a solid angle covers is W H / (4 tan_x tan_y cos^3).
  const float cos = z / d;
  const float importance = float(cam.width) * float(cam.height) /
                           (4.f * cam.tan_half_x * cam.tan_half_y * cos * cos * cos);
  out.push_back({fx, fy, flux * tr * f * (importance / d2), light, kind});
}

// BSDF values are for radiance (bsdf.h): a refraction divides by eta'^2,
// the ratio of the indices, because radiance is compressed into a smaller
// solid angle. The light's flux is not (Veach 1997, section 5.2): undone here.
float importance_scale(const Bsdf& bsdf, const Vec3& wo, const BsdfSample& s) {
  const auto* glass = std::get_if<DielectricBsdf>(&bsdf);
  if (!glass || !s.is_transmission) return 1.f;
  const float etap = wo.z > 0.f ? glass->eta : 1.f / glass->eta;
  return etap * etap;
}

}  // namespace

bool first_event_light_traced(const Bsdf& bsdf) {
  return std::holds_alternative<DiffuseBsdf>(bsdf);
}

bool light_tracing_pays_off(const Scene& scene) {
  if (!light_tracing_applies(scene) || scene.media.has_emission()) return false;
  // A camera inside a scattering medium receives splats from vertices
  // arbitrarily close to it (1 / d^2 with nothing to cancel it).
  if (!scene.media.coefficients(scene.camera.position).sigma_s.is_black()) return false;
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (light_is_traced(scene, i) &&
        !scene.media.coefficients(*scene.light_sampler.bounds()[i]->aim()).sigma_s.is_black())
      return true;
  return false;
}

bool light_tracing_takes_every_light(const Scene& scene) {
  if (scene.media.has_emission()) return false;
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (!light_is_traced(scene, i)) return false;
  return true;
}

namespace {

// Media, no motion blur, and a light that subpaths start at.
bool light_subpaths_apply(const Scene& scene) {
  if (scene.media.empty() || scene.motion_blur) return false;
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (light_is_traced(scene, i)) return true;
  return false;
}

}  // namespace

bool photon_merging_applies(const Scene& scene) { return light_subpaths_apply(scene); }

bool light_tracing_applies(const Scene& scene) {
  return scene.camera.lens_radius == 0.f && light_subpaths_apply(scene);
}

namespace {

// One light subpath's random walk: on_medium(y, flux, light, phase, dir)
// at each scattering vertex in a medium and on_surface(hit, flux, light,
// bsdf, dir) at each surface it reaches, with `flux` the subpath's weight
// arriving there and `dir` the direction it arrived along; `events` counts
// the vertex itself.
template <typename OnMedium, typename OnSurface>
void walk_light_path(const Scene& scene, const PathTracerOptions& options, Sampler& sampler,
                     uint32_t& rays, const OnMedium& on_medium, const OnSurface& on_surface) {
  const std::optional<LightRayStart> start = sample_light_ray(scene, sampler);
  if (!start) return;
  Ray ray{start->origin, start->dir, kInfinity, 0.f};
  Rgb beta(1.f);  // scattering weights so far (Russian roulette reads it)
  Rgb flux;       // beta times the light's: set at the first vertex
  for (int events = 1; events <= options.max_depth; ++events) {
    const std::optional<SurfaceHit> hit = scene.accel->intersect(ray);
    ++rays;
    thread_local std::vector<MajorantSpan> spans;
    scene.media.majorant_spans(ray, hit ? hit->t : kInfinity, spans);
    const FreeFlight flight = sample_free_flight(scene.media, spans, ray, sampler, beta);
    if (flight.event == FlightEvent::Absorbed) return;
    if (flight.event == FlightEvent::Escaped && (!hit || hit->light >= 0)) return;
    const Vec3 y =
        flight.event == FlightEvent::Scattered ? ray.origin + ray.dir * flight.t : hit->p;
    if (events == 1) {
      const Rgb intensity = light_ray_intensity(scene, *start, y);
      if (intensity.is_black()) return;
      flux = intensity * start->weight;
    }
    if (flight.event == FlightEvent::Scattered) {
      const HgPhase phase{flight.g};
      on_medium(y, flux * beta, start->light, phase, ray.dir, events);
      if (events == options.max_depth) return;
      const Vec3 wi = phase.sample(-ray.dir, sampler.next2());  // f / pdf = 1
      ray = Ray{y, wi, kInfinity, 0.f};
    } else {
      // A surface: the subpath goes on by BSDF sampling, light arriving
      // along ray.dir and leaving along the sampled direction. Vesper
      // shades with the geometric normal (bsdf_shading_normal), so the
      // BSDFs are symmetric but for refraction (importance_scale).
      const Bsdf& bsdf = scene.materials[hit->material];
      on_surface(*hit, flux * beta, start->light, bsdf, ray.dir, events);
      if (events == options.max_depth) return;
      const Vec3 n = bsdf_shading_normal(bsdf, hit->n, -ray.dir);
      const Frame frame = Frame::from_normal(n);
      const Vec3 wo = frame.to_local(-ray.dir);
      const float uc = sampler.next1();
      const auto bs = bsdf_sample(bsdf, wo, uc, sampler.next2());
      if (!bs || bs->pdf <= 0.f || bs->f.is_black()) return;
      beta *= bs->f * (std::abs(bs->wi.z) / bs->pdf * importance_scale(bsdf, wo, *bs));
      const Vec3 wi = normalize(frame.to_world(bs->wi));
      const Vec3 n_off = dot(wi, hit->n) >= 0.f ? hit->n : -hit->n;
      ray = Ray{offset_ray_origin(hit->p, n_off), wi, kInfinity, 0.f};
    }
    if (events + 1 >= options.rr_start_depth) {
      const float q = std::max(0.05f, 1.f - beta.max_component());
      if (sampler.next1() < q) return;
      beta *= 1.f / (1.f - q);
    }
    if (!beta.is_finite()) return;
  }
}

}  // namespace

void trace_light_path(const Scene& scene, const PathTracerOptions& options, Sampler& sampler,
                      uint32_t& rays, std::vector<CameraSplat>& out) {
  walk_light_path(
      scene, options, sampler, rays,
      [&](const Vec3& y, const Rgb& flux, size_t light, const HgPhase& phase, const Vec3& dir,
          int events) {
        if (events < options.light_traced_from) return;
        connect_to_camera(scene, y, flux, light, FirstEvent::Volume, sampler, rays, out,
                          [&](const Vec3& to_cam) {
                            return std::pair{Rgb(phase.eval(to_cam, -dir)), y};
                          });
      },
      [&](const SurfaceHit& hit, const Rgb& flux, size_t light, const Bsdf& bsdf, const Vec3& dir,
          int events) {
        if (events < options.light_traced_from || !first_event_light_traced(bsdf)) return;
        connect_to_camera(scene, hit.p, flux, light, FirstEvent::Diffuse, sampler, rays, out,
                          [&](const Vec3& to_cam) {
                            const Vec3 n = bsdf_shading_normal(bsdf, hit.n, to_cam);
                            const Frame frame = Frame::from_normal(n);
                            const Vec3 wo = frame.to_local(to_cam), wi = frame.to_local(-dir);
                            const Vec3 n_off = dot(to_cam, hit.n) >= 0.f ? hit.n : -hit.n;
                            return std::pair{bsdf_eval(bsdf, wo, wi) * std::abs(wo.z),
                                             offset_ray_origin(hit.p, n_off)};
                          });
      });
}

void trace_photon_path(const Scene& scene, const PathTracerOptions& options, Sampler& sampler,
                       uint32_t& rays, std::vector<Photon>& out) {
  walk_light_path(
      scene, options, sampler, rays,
      [&](const Vec3& y, const Rgb& flux, size_t light, const HgPhase&, const Vec3& dir,
          int events) {
        // Divided by sigma_s where it landed (photons land with density
        // proportional to it): grid media's thin parts then take no weight
        // from their dense neighbours' photons (photon_merging.h).
        if (events < options.light_traced_from) return;
        const Rgb sigma_s = scene.media.coefficients(y, 0.f).sigma_s;
        out.push_back({y, dir, safe_ratio(flux, sigma_s), uint32_t(light)});
      },
      [&](const SurfaceHit& hit, const Rgb& flux, size_t light, const Bsdf& bsdf, const Vec3& dir,
          int events) {
        if (events >= options.light_traced_from && first_event_light_traced(bsdf))
          out.push_back({hit.p, dir, flux, uint32_t(light), hit.n});
      });
}

}  // namespace vesper
