#pragma once
// Render space: (world - origin) / unit_scale, with the origin at the camera
// and unit_scale the radius of the scene around it (scene.h says why).
#include "renderer/math/vec.h"
#include "renderer/scene/scene_description.h"

namespace vesper {

struct RenderSpace {
  Vec3d origin;           // world position of render-space (0,0,0)
  double unit_scale = 1;  // world units per render-space unit
  double inv_scale = 1;
  float radius = 1;  // bounding radius of the render-space scene around the origin

  Vec3 point(const Vec3d& p) const { return Vec3((p - origin) * inv_scale); }
  Vec3 vector(const Vec3d& v) const { return Vec3(v * inv_scale); }
  // Radiant intensities fall off with distance squared: multiplied by this,
  // a light's power does not depend on the unit scale.
  float intensity_scale() const { return float(inv_scale * inv_scale); }
};

// The farthest from the world origin, on any axis, that a shape, light or
// bounded medium may reach: a million times beyond any real scene, and far
// enough inside the double range that the scene's radius and the render-space
// scale stay finite (a mesh scaled by 1.8e308 made them infinite, and every
// position in render space with them).
inline constexpr double kMaxWorldCoordinate = 1e30;
// The largest |coordinate| of the world-space extent of a shape, light or
// medium: 0 when it has none (a sun, an unbounded medium), infinity for NaN.
double extent_of(const ShapeDesc& shape);
double extent_of(const LightDesc& light);
double extent_of(const MediumDesc& medium);

// The render space of a scene: camera at the origin, everything with a
// position (shapes, lights, bounded media) within unit distance.
RenderSpace make_render_space(const SceneDescription& desc);

}  // namespace vesper
