#pragma once
// Light tracing (the t = 1 strategy of bidirectional path tracing): light
// subpaths from point and spot lights, each medium and diffuse-surface
// vertex connected to the camera. It takes a fixed part of path space,
// which the camera paths then leave out (PathTracerOptions::
// light_traced_from): paths whose first event after the camera is in a
// medium or on a diffuse surface, with at least that many scattering
// events, from a light that light subpaths start at (light_is_traced). In
// fog lit by a small light these are the random walk's deep paths, whose
// camera-side estimate is the noise that is left (bench/README.md); a light
// subpath reaches many pixels with bounded contributions (no 1 / r^2 at the
// light, the camera outside the fog).
#include <vector>

#include "renderer/integrator/path_tracer.h"
#include "renderer/integrator/photon_map.h"

namespace vesper {

// One connection to the camera: `value` lands at raster point (fx, fy) and
// is spread over the pixels by the film's filter (filter_splat,
// light_tracer_splat.h).
struct CameraSplat {
  float fx = 0, fy = 0;
  Rgb value;
  size_t light = 0;
  FirstEvent kind = FirstEvent::Volume;  // the camera path's first event: Volume or Diffuse
};

// Traces one light subpath and appends its camera connections to `out`.
// The splats' filtered sum in a pixel estimates that pixel (the camera's
// importance covers the whole raster): the film divides by the number of
// subpaths. Pinhole camera, no motion blur (light_tracing_applies).
void trace_light_path(const Scene& scene, const PathTracerOptions& options, Sampler& sampler,
                      uint32_t& rays, std::vector<CameraSplat>& out);

// Traces one light subpath as trace_light_path does and appends the
// vertices it would connect to the camera (in media and on diffuse
// surfaces, from light_traced_from events on) as photons (photon_merging.h).
void trace_photon_path(const Scene& scene, const PathTracerOptions& options, Sampler& sampler,
                       uint32_t& rays, std::vector<Photon>& out);

// Whether a camera path's first event at a surface of this BSDF leaves the
// path to the light tracer (as one in a medium does): diffuse surfaces,
// whose light the light tracer spreads evenly; glossy ones stay with the
// camera paths.
bool first_event_light_traced(const Bsdf& bsdf);

// Whether light tracing can take part: a pinhole camera that does not move,
// a light that subpaths start at, and media.
bool light_tracing_applies(const Scene& scene);

// Whether photon merging (photon_merging.h) can take part: media, a light
// that subpaths start at, and no motion blur (photons carry no time).
bool photon_merging_applies(const Scene& scene);

// The default (RenderOptions::light_traced_from unset): from how many
// events, and where, light tracing paid for itself in vesper_volume_bench:
// where a point or spot light sits inside a scattering medium (point-fog,
// the lantern in its cloud: the paths near the light, heavy-tailed for
// camera paths, start there with bounded weights), the camera is outside
// every medium and no medium emits. Not fog-shafts (its spot above the
// fog: 1.35x slower at equal error), the smoke (its light outside the
// voxels: 1.32x), the night room (the camera in the fog, whose nearby
// splats are fireflies: 34x).
inline constexpr int kLightTracedFrom = 2;
bool light_tracing_pays_off(const Scene& scene);

// Whether light subpaths start at every light and no medium emits: camera
// paths left with only light-traced paths can end
// (PathTracerOptions::light_traced_all).
bool light_tracing_takes_every_light(const Scene& scene);

}  // namespace vesper
