#pragma once
// What each step of one camera path reads and writes. Shared by the surface
// steps (path_tracer.cpp) and the medium steps (medium_step.cpp).
#include "renderer/integrator/path_tracer.h"

namespace vesper {

// The path between two scattering events.
struct PathState {
  Ray ray;
  Rgb throughput{1.f};
  bool count_emission_fully = true;  // camera ray or delta bounce: no MIS partner
  float prev_scatter_pdf = 0.f;      // of the BSDF or phase sample that made `ray`
};

struct PathContext {
  const Scene& scene;
  Sampler& sampler;
  const PathTracerOptions& options;
  PathResult& result;

  bool have_lights() const { return !scene.light_sampler.empty(); }

  // Adds a contribution to the pixel and, for layers/AOVs, to the path record.
  void add(const Rgb& value, int events, int group, bool volume_view = false,
           const Rgb* diffuse_fraction = nullptr) {
    result.radiance += value;
    if (options.record) options.record->add(value, events, group, volume_view, diffuse_fraction);
  }
};

}  // namespace vesper
