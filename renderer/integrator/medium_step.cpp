#include "renderer/integrator/medium_step.h"

#include <limits>
#include <optional>
#include <tuple>
#include <vector>

#include "renderer/integrator/direct_lighting.h"
#include "renderer/integrator/equiangular_sampling.h"
#include "renderer/integrator/light_vertex_connection.h"
#include "renderer/integrator/photon_merging.h"
#include "renderer/integrator/sun_shaft.h"
#include "renderer/integrator/volume_tracking.h"
#include "renderer/media/henyey_greenstein.h"

namespace vesper {
namespace {

// Adds the equiangular estimate along ray. At depth 0 its scattering would be
// the path's first event: a volume one, whatever the path does next.
void add_equiangular(PathContext& ctx, const std::vector<MajorantSpan>& spans, int depth,
                     const PathState& path) {
  const Ray& ray = path.ray;
  EquiangularSample es = sample_equiangular(ctx.scene, ray, spans, path.throughput, ctx.sampler,
                                            ctx.result.rays, ctx.options.equiangular_in_cone);
  if (es.value.is_black() || ctx.light_traced(depth + 1, es.light)) return;
  es.value *= 1.f - ctx.light_vertex_share(path, ray.origin + ray.dir * es.t, Vec3(0.f), Vec3(0.f),
                                           es.light, es.light_point);
  const int group = ctx.scene.light_group[es.light];
  if (depth == 0 && ctx.options.record) {
    ctx.add_as(FirstEvent::Volume, false, group, es.value);
  } else {
    ctx.add(es.value, depth + 1, group);
  }
}

// Adds the sun-shaft estimate along ray (sun_shaft.h), as add_equiangular.
void add_sun_shaft(PathContext& ctx, const std::vector<MajorantSpan>& spans, double shaft_depth,
                   int depth, const PathState& path) {
  const SunShaftSample s = sample_sun_shaft(ctx.scene, path.ray, spans, shaft_depth,
                                            path.throughput, ctx.sampler, ctx.result.rays);
  if (s.value.is_black()) return;
  const int group = ctx.scene.light_group[s.light];
  if (depth == 0 && ctx.options.record) {
    ctx.add_as(FirstEvent::Volume, false, group, s.value);
  } else {
    ctx.add(s.value, depth + 1, group);
  }
}

// Next-event estimation from the point at distance t along path.ray, where
// the path scattered. Delta lights are weighted against equiangular sampling
// when it ran on this ray, and against light-vertex connections from the
// vertex that made the ray. Returns the light choice's sums, for the MIS
// weight of the phase ray that leaves this point.
LightSampler::Sums add_direct_light(PathContext& ctx, const std::vector<MajorantSpan>& spans,
                                    float t, const HgPhase& phase, bool equiangular,
                                    float shaft_ratio, int depth, const PathState& path) {
  const Scene& scene = ctx.scene;
  const Ray& ray = path.ray;
  const Vec3 p = ray.origin + ray.dir * t;
  const Vec3 wo = -ray.dir;
  auto eval_phase = [&](const Vec3& wi) {
    const float f = phase.eval(wo, wi);
    return std::tuple{Rgb(f), Rgb{}, f};
  };
  // Delta lights: the complement of sample_equiangular's weight at this t
  // (its header says why any such partition of unity is unbiased); where
  // equiangular cannot pick t this strategy takes it all, also when the
  // proxy has underflowed (power_heuristic(0, 0) would drop it). Times the
  // path tracer's share against light-vertex connections (light_vertex.h).
  auto delta_weight = [&](size_t li, const Vec3& light_point) {
    float w = 1.f;
    if (equiangular) {
      const float pdf_e = equiangular_pdf(scene.light_sampler.bounds()[li], ray, spans, t,
                                          ctx.options.equiangular_in_cone);
      if (pdf_e > 0.f)
        w = power_heuristic(distance_sampling_proxy_pdf(scene.media, spans, ray, t), pdf_e);
    }
    return w * (1.f - ctx.light_vertex_share(path, p, Vec3(0.f), Vec3(0.f), li, light_point));
  };
  auto shaft = [&](size_t li) { return shaft_ratio * shaft_light_pmf(scene, li); };
  const DirectSample ds =
      sample_direct<true>(scene, ShadingPoint{p, Vec3(0.f)}, Vec3(0.f), ray.time, ctx.sampler,
                          ctx.result.rays, eval_phase, delta_weight, shaft);
  if (!ds.value.is_black() && !ctx.light_traced(depth + 1, ds.light))
    ctx.add(path.throughput * ds.value, depth + 1, scene.light_group[ds.light]);
  return ds.selection;
}

// The connection from a medium vertex to the sample's light vertex.
void connect_from_medium(PathContext& ctx, const Vec3& p, const HgPhase& phase, const Vec3& wo,
                         int depth, const PathState& path) {
  const LightVertex* lv = ctx.get_light_vertex(path.ray.time);
  if (!lv || ctx.light_traced(depth + 2, lv->light)) return;
  const Rgb value = connect_light_vertex(ctx.scene, *lv, p, Vec3(0.f), path.ray.time, ctx.sampler,
                                         ctx.result.rays, ctx.strategies(), [&](const Vec3& wi) {
                                           const float f = phase.eval(wo, wi);
                                           return std::tuple{Rgb(f), f};
                                         });
  if (!value.is_black())
    ctx.add(path.throughput * value, depth + 2, ctx.scene.light_group[lv->light]);
}

// At a real scattering collision: light from there, then the next ray.
void scatter(PathContext& ctx, const std::vector<MajorantSpan>& spans, const FreeFlight& flight,
             bool equiangular, std::optional<double> shaft_depth, int depth, PathState& path) {
  const HgPhase phase{flight.g};
  const float shaft_ratio = shaft_depth ? shaft_to_tracking_ratio(ctx.scene.media, spans, path.ray,
                                                                  *shaft_depth, flight.t)
                                        : 0.f;
  std::optional<LightSampler::Sums> selection;
  if (ctx.have_lights() && !ctx.light_traced_all(depth + 1)) {
    selection =
        add_direct_light(ctx, spans, flight.t, phase, equiangular, shaft_ratio, depth, path);
  } else {
    // Keep the sample dimensions aligned whether or not NEE ran.
    ctx.sampler.next1();
    ctx.sampler.next2();
  }
  const Vec3 p = path.ray.origin + path.ray.dir * flight.t;
  const Vec3 wo = -path.ray.dir;
  if (depth == 0 && ctx.options.photons) merge_medium_photons(ctx, p, phase, wo, path);
  if (ctx.light_vertices && depth + 1 < ctx.options.max_depth && !ctx.light_traced_all(depth + 2))
    connect_from_medium(ctx, p, phase, wo, depth, path);
  const Vec3 wi = phase.sample(wo, ctx.sampler.next2());
  path.prev_scatter_pdf = phase.pdf(wo, wi);  // f / pdf = 1: throughput unchanged
  path.prev_vertex = ShadingPoint{p, Vec3(0.f)};
  path.prev_selection = selection;
  path.prev_shaft_ratio = shaft_ratio;
  path.count_emission_fully = false;
  path.ray = Ray{p, wi, std::numeric_limits<float>::infinity(), path.ray.time};
}

// Delta tracking to the next real collision, with the volume emission along
// the way (up to that collision) integrated on its own (volume_emission.h).
FreeFlight sample_free_flight_with_emission(PathContext& ctx,
                                            const std::vector<MajorantSpan>& spans, float tmax,
                                            int depth, PathState& path) {
  const MediaSet& media = ctx.scene.media;
  if (!media.has_emission())
    return sample_free_flight(media, spans, path.ray, ctx.sampler, path.throughput);
  const float u = ctx.sampler.next1();  // the emission lattice's offset
  thread_local std::vector<ThroughputStep> steps;
  steps.clear();
  const FreeFlight flight =
      sample_free_flight(media, spans, path.ray, ctx.sampler, path.throughput, &steps);
  const float t_end = flight.event == FlightEvent::Escaped ? tmax : flight.t;
  const Rgb emitted = integrate_emission(media, path.ray, t_end, steps, u);
  if (!emitted.is_black()) ctx.add(emitted, depth, ctx.scene.emission_group, depth == 0);
  return flight;
}

}  // namespace

MediumEvent sample_medium(PathContext& ctx, float tmax, int depth, PathState& path) {
  const Scene& scene = ctx.scene;
  const PathTracerOptions& options = ctx.options;
  thread_local std::vector<MajorantSpan> spans;
  scene.media.majorant_spans(path.ray, tmax, spans);
  if (depth == 0 && options.want_camera_transmittance)
    ctx.result.camera_transmittance =
        estimate_transmittance(scene.media, path.ray, tmax, ctx.sampler).average();
  // Equiangular sampling needs a light it can aim at (a point or a sphere).
  const bool equiangular = options.equiangular && !spans.empty() &&
                           scene.light_sampler.has_aimable() && depth < options.max_depth;
  if (equiangular && !ctx.light_traced_all(depth + 1)) add_equiangular(ctx, spans, depth, path);
  // Sun shafts: the spans' optical depth, once for the sample and the weights.
  std::optional<double> shaft_depth;
  if (options.sun_shafts && depth < options.max_depth && sun_shafts_apply(scene, spans)) {
    shaft_depth = shaft_optical_depth(scene.media, spans, path.ray);
    add_sun_shaft(ctx, spans, *shaft_depth, depth, path);
  }

  const FreeFlight flight = sample_free_flight_with_emission(ctx, spans, tmax, depth, path);
  if (flight.event == FlightEvent::Absorbed) return MediumEvent::PathEnded;
  if (flight.event == FlightEvent::Escaped) return MediumEvent::None;
  if (depth >= options.max_depth) return MediumEvent::PathEnded;
  if (depth == 0) ctx.first_event_splattable = true;
  if (depth == 0 && options.record) options.record->set_first_volume();
  scatter(ctx, spans, flight, equiangular, shaft_depth, depth, path);
  return MediumEvent::Scattered;
}

}  // namespace vesper
