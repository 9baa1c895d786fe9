#include "renderer/integrator/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>

#include "renderer/integrator/direct_lighting.h"
#include "renderer/integrator/light_tracer.h"
#include "renderer/integrator/light_vertex_connection.h"
#include "renderer/integrator/medium_step.h"
#include "renderer/integrator/path_context.h"
#include "renderer/integrator/photon_merging.h"
#include "renderer/integrator/sun_shaft.h"
#include "renderer/math/frame.h"

namespace vesper {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Radiance from light li reached by path.ray `distance` away (infinity: the
// ray escaped), MIS-weighted against the BSDF or phase sample that made the
// ray.
void add_light_reached(PathContext& ctx, size_t li, float distance, int depth,
                       const PathState& path) {
  const Scene& scene = ctx.scene;
  const Light& light = scene.lights[li];
  const Rgb le = light.emitted(path.ray.dir);
  if (le.is_black() || ctx.light_traced(depth, li)) return;
  float w = 1.f;
  if (!path.count_emission_fully) {
    const float pmf = path.prev_selection
                          ? scene.light_sampler.pmf(path.prev_vertex, li, *path.prev_selection)
                          : scene.light_sampler.pmf(path.prev_vertex, li);
    const float light_pdf = pmf * light.pdf(path.ray.dir, distance);
    w = power_heuristic(path.prev_scatter_pdf, light_pdf);
    // A sun that sun shafts sampled from the ray that made the vertex.
    if (path.prev_shaft_ratio > 0.f && light.is_sun()) {
      const float shaft_pdf =
          path.prev_shaft_ratio * shaft_light_pmf(scene, li) * light.pdf(path.ray.dir, distance);
      w = power_heuristic(path.prev_scatter_pdf, light_pdf, shaft_pdf);
    }
  }
  ctx.add(path.throughput * le * w, depth, scene.light_group[li]);
}

// AOVs and alpha of the camera ray's first hit.
void record_first_hit(PathContext& ctx, const SurfaceHit& hit, const Ray& ray) {
  ctx.result.alpha = 1.f;
  ctx.result.first_shape = hit.shape;
  if (!ctx.options.want_aovs) return;
  ctx.result.depth = float(hit.t * ctx.scene.unit_scale);
  ctx.result.normal = dot(hit.n, ray.dir) < 0.f ? hit.n : -hit.n;
}

// Next-event estimation at a surface vertex. Delta and sphere lights share
// the path x -> hit -> light with light-vertex connections made from the
// vertex x before (light_vertex.h).
template <bool kMedia>
LightSampler::Sums add_direct_light(PathContext& ctx, const SurfaceHit& hit, const ShadingPoint& at,
                                    const Bsdf& bsdf, const Frame& frame, const Vec3& wo, int depth,
                                    const PathState& path) {
  const bool want_diffuse = ctx.options.record != nullptr;
  auto delta_weight = [&](size_t li, const Vec3& light_point) {
    return 1.f - ctx.light_vertex_share(path, hit.p, hit.n, at.n, li, light_point);
  };

  const DirectSample ds = sample_direct<kMedia>(
      ctx.scene, at, hit.n, path.ray.time, ctx.sampler, ctx.result.rays,
      [&](const Vec3& wi_world) {
        const Vec3 wi = frame.to_local(wi_world);
        const float cos = std::abs(wi.z);
        return std::tuple{bsdf_eval(bsdf, wo, wi) * cos,
                          want_diffuse ? bsdf_eval_diffuse(bsdf, wo, wi) * cos : Rgb{},
                          bsdf_pdf(bsdf, wo, wi)};
      },
      delta_weight);
  if (ds.value.is_black() || ctx.light_traced(depth + 1, ds.light)) return ds.selection;
  const Rgb fraction = safe_ratio(ds.diffuse, ds.value);
  ctx.add(path.throughput * ds.value, depth + 1, ctx.scene.light_group[ds.light], false,
          depth == 0 ? &fraction : nullptr);
  return ds.selection;
}

// The connection from a surface vertex to the sample's light vertex.
void connect_from_surface(PathContext& ctx, const SurfaceHit& hit, const Bsdf& bsdf,
                          const Frame& frame, const Vec3& wo, int depth, const Rgb& throughput,
                          float time) {
  const LightVertex* lv = ctx.get_light_vertex(time);
  if (!lv || ctx.light_traced(depth + 2, lv->light)) return;
  const Rgb value = connect_light_vertex(
      ctx.scene, *lv, hit.p, hit.n, time, ctx.sampler, ctx.result.rays, ctx.strategies(),
      [&](const Vec3& wi_world) {
        const Vec3 wi = frame.to_local(wi_world);
        return std::tuple{bsdf_eval(bsdf, wo, wi) * std::abs(wi.z), bsdf_pdf(bsdf, wo, wi)};
      });
  if (value.is_black()) return;
  // At the first surface its own lobe split, as next-event estimation's.
  Rgb fraction;
  if (depth == 0 && ctx.options.record) {
    const Vec3 wi = frame.to_local(normalize(lv->p - hit.p));
    fraction = safe_ratio(bsdf_eval_diffuse(bsdf, wo, wi), bsdf_eval(bsdf, wo, wi));
  }
  ctx.add(throughput * value, depth + 2, ctx.scene.light_group[lv->light], false,
          depth == 0 ? &fraction : nullptr);
}

// Light sampling and a BSDF sample for the next ray at a surface vertex;
// false when the path ends there.
template <bool kMedia>
bool scatter_at_surface(PathContext& ctx, const SurfaceHit& hit, int depth, PathState& path) {
  const Bsdf& bsdf = ctx.scene.materials[hit.material];
  const Vec3 wo_world = -path.ray.dir;
  const bool transmissive = bsdf_transmits(bsdf);
  const Vec3 n_shading = bsdf_shading_normal(bsdf, hit.n, wo_world);
  const Frame frame = Frame::from_normal(n_shading);
  const Vec3 wo = frame.to_local(wo_world);
  if (depth == 0 && ctx.options.want_aovs) ctx.result.albedo = bsdf_albedo(bsdf);
  if constexpr (kMedia)
    if (depth == 0 && ctx.options.light_traced_from > 0)
      ctx.first_event_splattable = first_event_light_traced(bsdf);
  // An opaque BSDF reflects only on the viewer's side: lights wholly behind
  // it can be skipped; light through a dielectric may come from anywhere.
  const ShadingPoint at{hit.p, transmissive ? Vec3(0.f) : n_shading};
  if constexpr (kMedia)
    if (depth == 0 && ctx.options.photons && ctx.first_event_splattable)
      merge_surface_photons(ctx, hit.p, hit.n, bsdf, frame, wo, path);

  std::optional<LightSampler::Sums> selection;
  if (ctx.have_lights() && !bsdf_is_delta(bsdf)) {
    selection = add_direct_light<kMedia>(ctx, hit, at, bsdf, frame, wo, depth, path);
  } else {
    // Keep the sample dimensions aligned whether or not NEE ran.
    ctx.sampler.next1();
    ctx.sampler.next2();
  }

  // Whatever the BSDF sample below does: the path tracer's share of the
  // connection's paths assumes it was made.
  if constexpr (kMedia)
    if (ctx.light_vertices && !bsdf_is_delta(bsdf) && depth + 1 < ctx.options.max_depth &&
        !ctx.light_traced_all(depth + 2))
      connect_from_surface(ctx, hit, bsdf, frame, wo, depth, path.throughput, path.ray.time);

  const float uc = ctx.sampler.next1();
  const Vec2 u = ctx.sampler.next2();
  const auto bs = bsdf_sample(bsdf, wo, uc, u);
  if (!bs || bs->pdf <= 0.f || bs->f.is_black()) return false;
  if (depth == 0 && ctx.options.record)
    ctx.options.record->set_first_surface(
        bs->is_specular ? Rgb{} : safe_ratio(bsdf_eval_diffuse(bsdf, wo, bs->wi), bs->f));
  path.throughput *= bs->f * (std::abs(bs->wi.z) / bs->pdf);
  path.count_emission_fully = bs->is_specular;
  path.prev_scatter_pdf = bs->pdf;
  path.prev_vertex = at;
  path.prev_selection = selection;
  path.prev_shaft_ratio = 0.f;

  const Vec3 wi_world = normalize(frame.to_world(bs->wi));
  const Vec3 n_off = dot(wi_world, hit.n) >= 0.f ? hit.n : -hit.n;
  path.ray = Ray{offset_ray_origin(hit.p, n_off), wi_world, kInfinity, path.ray.time};
  return true;
}

// Continues the path (Russian roulette); false = terminated.
bool russian_roulette(int depth, const PathTracerOptions& options, Sampler& sampler,
                      Rgb& throughput) {
  if (depth + 1 >= options.rr_start_depth) {
    const float q = std::max(0.05f, 1.f - throughput.max_component());
    if (sampler.next1() < q) return false;
    throughput *= 1.f / (1.f - q);
  }
  return throughput.is_finite();
}

template <bool kMedia>
PathResult trace(const Scene& scene, const Ray& camera_ray, Sampler& sampler,
                 const PathTracerOptions& options) {
  PathResult result;
  if (options.record) options.record->reset();
  PathContext ctx{scene, sampler, options, result, Rgb{}, Rgb{}};
  if constexpr (kMedia) ctx.light_vertices = options.light_vertices;
  PathState path{camera_ray};
  for (int depth = 0;; ++depth) {
    if constexpr (kMedia)
      if (ctx.light_traced_all(depth)) break;
    const std::optional<SurfaceHit> hit = scene.accel->intersect(path.ray);
    ++result.rays;
    if (depth == 0 && hit) record_first_hit(ctx, *hit, path.ray);
    if constexpr (kMedia) {
      const MediumEvent event = sample_medium(ctx, hit ? hit->t : kInfinity, depth, path);
      if (event == MediumEvent::PathEnded) break;
      if (event == MediumEvent::Scattered) {
        if (!russian_roulette(depth, options, sampler, path.throughput)) break;
        continue;
      }
    }
    if (!hit) {
      for (uint32_t li : scene.infinite_lights) add_light_reached(ctx, li, kInfinity, depth, path);
      break;
    }
    // Emitters are one-sided and do not reflect: the path ends here.
    if (hit->light >= 0) {
      add_light_reached(ctx, size_t(hit->light), hit->t, depth, path);
      break;
    }
    if (depth >= options.max_depth) break;
    if (!scatter_at_surface<kMedia>(ctx, *hit, depth, path)) break;
    if (!russian_roulette(depth, options, sampler, path.throughput)) break;
  }
  ctx.clamp_indirect();
  return result;
}

}  // namespace

PathResult trace_path(const Scene& scene, const Ray& camera_ray, Sampler& sampler,
                      const PathTracerOptions& options) {
  // Scenes without media get a path tracer compiled without any medium code.
  return scene.media.empty() ? trace<false>(scene, camera_ray, sampler, options)
                             : trace<true>(scene, camera_ray, sampler, options);
}

}  // namespace vesper
