#pragma once
// Ray queries against the scene's surfaces through an Embree BVH (robust mode).
// Embree stays behind this header (core/embree_scene.h builds the BVH).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "renderer/core/accel_geometry.h"
#include "renderer/core/ray.h"

namespace vesper {

struct SurfaceHit {
  Vec3 p;  // hit point, refined (on the sphere, from barycentrics)
  Vec3 n;  // unit geometric normal: cross(edge1, edge2), triangle winding, sphere outward
  float t = 0;
  uint32_t material = 0;
  int32_t light = -1;  // index into Scene::lights when the surface is an emitter
  int32_t shape = -1;  // index into the scene's shapes (Cryptomatte); -1 for emitters
};

class Accel {
 public:
  Accel(std::vector<AccelQuad> quads, std::vector<AccelSphere> spheres,
        std::vector<AccelMesh> meshes);
  ~Accel();
  Accel(const Accel&) = delete;
  Accel& operator=(const Accel&) = delete;

  // Moving primitives are met where they are at ray.time.
  std::optional<SurfaceHit> intersect(const Ray& ray) const;
  // True when anything blocks the segment origin + t*dir, t in (0, tmax), at `time`.
  bool occluded(const Vec3& origin, const Vec3& dir, float tmax, float time = 0.f) const;
  // Number of triangles/quads/spheres in the BVH.
  size_t primitive_count() const;
  // The geometry in the BVH (degenerate primitives dropped), in render space:
  // what the benchmark builds its raw EmbreeScene from.
  const AccelGeometry& geometry() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Sets flush-to-zero and denormals-are-zero on the calling thread, as Embree
// recommends; the render loop calls it on every worker thread.
void set_flush_to_zero();

}  // namespace vesper
