#pragma once
// The surfaces handed to the accelerator, already in render space: quads
// (walls and quad emitters), spheres and triangle meshes.
//
// Motion blur: a primitive that moves over the shutter also holds its shape
// at K >= 2 time steps spread uniformly over the shutter (step k at shutter
// time k / (K - 1)); Embree interpolates its vertices linearly between steps
// at the ray's time (core/motion_steps.h does the same for the hit point).
// Empty steps = a still primitive, built exactly as without motion blur.
#include <array>
#include <cstdint>
#include <vector>

#include "renderer/math/vec.h"

namespace vesper {

struct AccelQuad {
  Vec3 corner, edge1, edge2;
  uint32_t material = 0;
  int32_t light = -1;  // index into Scene::lights when the quad is an emitter
  int32_t shape = -1;  // index into the scene's shapes; -1 for emitters
  struct Step {
    Vec3 corner, edge1, edge2;
  };
  std::vector<Step> steps = {};  // motion blur; empty = still
};
struct AccelSphere {
  Vec3 center;
  float radius = 1;
  uint32_t material = 0;
  int32_t shape = -1;  // index into the scene's shapes
  struct Step {
    Vec3 center;
    float radius = 1;
  };
  std::vector<Step> steps = {};  // motion blur; empty = still
};
struct AccelMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<uint32_t, 3>> triangles;
  uint32_t material = 0;
  int32_t shape = -1;  // index into the scene's shapes
  // Motion blur: the positions at each step (same count and order); empty = still.
  std::vector<std::vector<Vec3>> steps = {};
};

struct AccelGeometry {
  std::vector<AccelQuad> quads;
  std::vector<AccelSphere> spheres;
  std::vector<AccelMesh> meshes;

  // Quads + spheres + triangles.
  size_t primitive_count() const {
    size_t n = quads.size() + spheres.size();
    for (const AccelMesh& m : meshes) n += m.triangles.size();
    return n;
  }
};

// Without what can never be hit meaningfully and has no normal: zero-area
// quads, degenerate or non-finite triangles, and meshes left empty.
inline AccelGeometry without_degenerate(AccelGeometry g) {
  std::erase_if(
      g.quads, [](const AccelQuad& q) { return !(length_squared(cross(q.edge1, q.edge2)) > 0.f); });
  for (AccelMesh& m : g.meshes) {
    std::erase_if(m.triangles, [&](const std::array<uint32_t, 3>& t) {
      const Vec3 c =
          cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
      return !(length_squared(c) > 0.f) || !is_finite(c);
    });
  }
  std::erase_if(g.meshes, [](const AccelMesh& m) { return m.triangles.empty(); });
  return g;
}

}  // namespace vesper
