#pragma once
// Unidirectional path tracing with next-event estimation and multiple
// importance sampling (power heuristic) between light and BSDF sampling.
#include "renderer/core/ray.h"
#include "renderer/math/rgb.h"
#include "renderer/sampling/sampler.h"
#include "renderer/scene/scene.h"

namespace vesper {

// What one camera path returns. AOV fields are filled only when asked for.
struct PathResult {
  Rgb radiance;
  float alpha = 0;    // 1 when the camera ray hit a surface, 0 for the background
  Rgb albedo;         // first-hit reflectance
  Vec3 normal;        // first-hit shading normal, world space, facing the camera
  float depth = 0;    // first-hit distance along the camera ray, scene units; 0 for a miss
  uint32_t rays = 0;  // intersection and occlusion queries traced
};

struct PathTracerOptions {
  int max_depth = 8;  // scattering events after the camera vertex
  bool want_aovs = false;
  int rr_start_depth = 3;  // Russian roulette from this many scattering events on
  bool equiangular =
      true;  // equiangular sampling toward point/spot lights in homogeneous media (MIS)
};

PathResult trace_path(const Scene& scene, const Ray& camera_ray, Sampler& sampler,
                      const PathTracerOptions& options);

}  // namespace vesper
