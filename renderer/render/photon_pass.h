#pragma once
// Photon merging's pass (integrator/photon_merging.h), traced before the
// camera pass: light subpaths for the whole frame (every sample index, one
// subpath per pixel each, as the light tracer's), whatever sample range
// this render takes, so that ranges read the same photons and still merge
// exactly. Internal to render/.
#include <cstdint>
#include <functional>

#include "renderer/integrator/path_tracer.h"
#include "renderer/integrator/photon_merging.h"

namespace vesper {

// Most light subpaths one frame traces for photons (memory: each leaves a
// few 40-byte photons).
inline constexpr uint64_t kMaxPhotonSubpaths = uint64_t(1) << 22;

// The light subpaths a frame of `frame_spp` samples per pixel traces.
uint64_t photon_subpaths(const Scene& scene, int frame_spp);

struct PhotonPassResult {
  PhotonMerging photons;
  uint64_t rays = 0, nonfinite = 0;  // nonfinite: photons dropped as NaN or Inf
};

// `radius` > 0 (render space) overrides photon_radius. `progress(n)` is called from worker
// threads as each n more subpaths are done.
PhotonPassResult trace_photons(const Scene& scene, const PathTracerOptions& pt, uint64_t seed,
                               int frame_spp, float radius, int threads,
                               const std::function<void(uint64_t)>& progress);

}  // namespace vesper
