#pragma once
// What each step of one camera path reads and writes. Shared by the surface
// steps (path_tracer.cpp) and the medium steps (medium_step.cpp).
#include <optional>

#include "renderer/integrator/light_vertex.h"
#include "renderer/integrator/path_tracer.h"

namespace vesper {

// The path between two scattering events.
struct PathState {
  Ray ray;
  Rgb throughput{1.f};
  bool count_emission_fully = true;  // camera ray or delta bounce: no MIS partner
  float prev_scatter_pdf = 0.f;      // of the BSDF or phase sample that made `ray`
  // Where that sample was made, as next-event estimation chose its light
  // there: a light the ray hits is MIS-weighted with the pmf of that vertex.
  ShadingPoint prev_vertex{};
  // The light choice's sums there, when next-event estimation ran at it.
  std::optional<LightSampler::Sums> prev_selection{};
  // Where prev_vertex is a medium vertex on a ray that sun shafts sampled:
  // their density there over delta tracking's (shaft_to_tracking_ratio), for
  // the MIS weight of a phase ray that reaches a sun. 0 otherwise.
  float prev_shaft_ratio = 0.f;
};

struct PathContext {
  const Scene& scene;
  Sampler& sampler;
  const PathTracerOptions& options;
  PathResult& result;

  // With options.indirect_clamp: the sample's direct and indirect sums.
  Rgb direct, indirect;

  // Light-vertex connections (light_vertex.h): on for this path, and the
  // sample's light vertex once traced (at the first vertex that connects).
  bool light_vertices = false;
  bool light_vertex_traced = false;
  std::optional<LightVertex> light_vertex{};

  // The camera path's first event is one the light tracer connects to the
  // camera: in a medium or on a diffuse surface (light_traced_from).
  bool first_event_splattable = false;
  // Whether the light tracer takes the path this contribution ends, of
  // `events` scattering events, at `light` (PathTracerOptions::light_traced_from).
  bool light_traced(int events, size_t light) const {
    return options.light_traced_from > 0 && first_event_splattable &&
           events >= options.light_traced_from && light_is_traced(scene, light);
  }
  // Whether the light tracer takes every path of `events` or more events
  // this camera path can still make: nothing is left for it to add.
  bool light_traced_all(int events) const {
    return options.light_traced_all && first_event_splattable &&
           events >= options.light_traced_from;
  }

  bool have_lights() const { return !scene.light_sampler.empty(); }
  PathStrategies strategies() const { return {options.equiangular, options.equiangular_in_cone}; }

  const LightVertex* get_light_vertex(float time) {
    if (!light_vertex_traced) {
      light_vertex = trace_light_vertex(scene, time, sampler, result.rays);
      light_vertex_traced = true;
    }
    return light_vertex ? &*light_vertex : nullptr;
  }
  // The connections' MIS share of the path x -> y -> light, x being the
  // vertex that made path.ray (0 where no connection was made from it): the
  // path tracer's own estimates of that path are scaled by 1 - this.
  float light_vertex_share(const PathState& path, const Vec3& y, const Vec3& n_y,
                           const Vec3& n_y_shading, size_t light, const Vec3& light_point) const {
    if (!light_vertices || path.count_emission_fully) return 0.f;
    return light_vertex_weight(scene, path.prev_vertex.p, path.prev_scatter_pdf, y, n_y,
                               n_y_shading, light, light_point, path.ray.time, strategies());
  }

  // Adds a contribution to the pixel and, for layers/AOVs, to the path record.
  void add(const Rgb& value, int events, int group, bool volume_view = false,
           const Rgb* diffuse_fraction = nullptr) {
    result.radiance += value;
    if (options.indirect_clamp > 0.f) (events > 1 ? indirect : direct) += value;
    if (options.record) options.record->add(value, events, group, volume_view, diffuse_fraction);
  }
  // A contribution whose first event the path has not made itself.
  void add_as(FirstEvent kind, bool is_indirect, int group, const Rgb& value) {
    result.radiance += value;
    if (options.indirect_clamp > 0.f) (is_indirect ? indirect : direct) += value;
    if (options.record) options.record->add_as(kind, is_indirect, group, value);
  }

  // The indirect sample clamp (render.clamp), once the path has ended: the
  // indirect sum is scaled (hue kept) so its largest component is at most
  // the clamp, in the pixel and in the record's indirect bins alike. An
  // unclamped sample keeps its radiance bit for bit.
  void clamp_indirect() {
    const float limit = options.indirect_clamp, peak = indirect.max_component();
    if (!(limit > 0.f) || !(peak > limit)) return;
    const float s = limit / peak;
    result.radiance = direct + indirect * s;
    if (options.record) options.record->scale_indirect(s);
  }
};

}  // namespace vesper
