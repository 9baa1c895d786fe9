#pragma once
// Unidirectional path tracing with next-event estimation and multiple
// importance sampling (power heuristic) between light and BSDF sampling.
#include "renderer/core/ray.h"
#include "renderer/integrator/path_record.h"
#include "renderer/math/rgb.h"
#include "renderer/sampling/sampler.h"
#include "renderer/scene/scene.h"

namespace vesper {

struct PhotonMerging;

// What one camera path returns. AOV fields are filled only when asked for.
struct PathResult {
  Rgb radiance;
  float alpha = 0;    // 1 when the camera ray hit a surface, 0 for the background
  Rgb albedo;         // first-hit reflectance
  Vec3 normal;        // first-hit shading normal, world space, facing the camera
  float depth = 0;    // first-hit distance along the camera ray, scene units; 0 for a miss
  uint32_t rays = 0;  // intersection and occlusion queries traced
  float camera_transmittance = 1;  // through the media to the first surface (RGB average)
  int32_t first_shape = -1;        // the shape the camera ray hits first (media ignored); -1: none
};

struct PathTracerOptions {
  int max_depth = 8;  // scattering events after the camera vertex
  bool want_aovs = false;
  int rr_start_depth = 3;  // Russian roulette from this many scattering events on
  // Equiangular sampling toward point/spot lights in all media (MIS).
  bool equiangular = true;
  // ... aimed only at the part of a ray inside a spot light's cone.
  bool equiangular_in_cone = true;
  // Sun shafts: next-event estimation toward suns from a distance sampled
  // on every ray through homogeneous media (sun_shaft.h).
  bool sun_shafts = true;
  // Connect scattering vertices to a light vertex traced from point and spot
  // lights (light_vertex.h), in scenes with media.
  bool light_vertices = true;
  // Layers and transport AOVs: when set, every contribution is also binned
  // here (reset by trace_path). Null for plain renders.
  PathRecord* record = nullptr;
  // > 0: the light tracer (light_tracer.h) takes the paths whose first event
  // is in a medium and that make at least this many scattering events, from
  // the lights it starts at: camera paths leave them out. 0 = off.
  int light_traced_from = 0;
  // ... and it takes every light: camera paths that can only make such paths
  // end.
  bool light_traced_all = false;
  // Photon merging (photon_merging.h; opt-in, biased): the photons that
  // take the light-traced paths (light_traced_from), in place of light
  // tracing's splats. Not owned.
  const PhotonMerging* photons = nullptr;
  // Estimate the camera ray's transmittance through the media (layer alpha).
  bool want_camera_transmittance = false;
  // > 0: a camera sample's indirect light (reached after two or more
  // scattering events) is scaled down so that its largest RGB component is at
  // most this (render.clamp; biased). 0 = off, the exact estimator.
  float indirect_clamp = 0;
};

PathResult trace_path(const Scene& scene, const Ray& camera_ray, Sampler& sampler,
                      const PathTracerOptions& options);

}  // namespace vesper
