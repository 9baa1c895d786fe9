#pragma once
// Ray queries against the scene's surfaces through an Embree BVH (robust mode).
// Embree stays behind this header: nothing else includes rtcore.h.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "renderer/core/ray.h"

namespace vesper {

struct SurfaceHit {
  Vec3 p;  // hit point, refined (on the sphere, from barycentrics)
  Vec3 n;  // unit geometric normal: cross(edge1, edge2), triangle winding, sphere outward
  float t = 0;
  uint32_t material = 0;
  int32_t light = -1;  // index into Scene::lights when the surface is an emitter
};

// Geometry handed to the accelerator, already in render space.
struct AccelQuad {
  Vec3 corner, edge1, edge2;
  uint32_t material = 0;
  int32_t light = -1;
};
struct AccelSphere {
  Vec3 center;
  float radius = 1;
  uint32_t material = 0;
};
struct AccelMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<uint32_t, 3>> triangles;  // degenerate ones are dropped by the accel
  uint32_t material = 0;
};

class Accel {
 public:
  Accel(std::vector<AccelQuad> quads, std::vector<AccelSphere> spheres,
        std::vector<AccelMesh> meshes);
  ~Accel();
  Accel(const Accel&) = delete;
  Accel& operator=(const Accel&) = delete;

  std::optional<SurfaceHit> intersect(const Ray& ray) const;
  // True when anything blocks the segment origin + t*dir, t in (0, tmax).
  bool occluded(const Vec3& origin, const Vec3& dir, float tmax) const;
  // Number of triangles/quads/spheres in the BVH.
  size_t primitive_count() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Sets flush-to-zero and denormals-are-zero on the calling thread, as Embree
// recommends; the render loop calls it on every worker thread.
void set_flush_to_zero();

}  // namespace vesper
