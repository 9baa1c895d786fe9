#pragma once
// An Embree scene (robust, high build quality) on its own device, built from
// render-space geometry: the BVH that vesper::Accel queries, and the one the
// ray-throughput benchmark traces raw rays against. The only header that
// exposes Embree (core/accel.h keeps it hidden from the rest of the renderer).
#include <embree3/rtcore.h>

#include <optional>
#include <vector>

#include "renderer/core/accel_geometry.h"
#include "renderer/core/rigid_motion.h"

namespace vesper {

class EmbreeScene {
 public:
  // Geometry ids, in order: geometry.quads, then spheres, then meshes. The
  // meshes' vertex and index buffers are shared, not copied: `geometry` must
  // outlive the scene and hold no degenerate primitives (without_degenerate).
  // A moving primitive (motion blur) is an instance of its step 0 with motion
  // transforms when its steps are affine images of it (core/rigid_motion.h),
  // else a geometry with one vertex buffer per step; either way at its id.
  explicit EmbreeScene(const AccelGeometry& geometry);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene scene() const { return scene_; }

 private:
  // Attaches the committed-to-be geometry, through an instance when `motion` is set.
  void attach(RTCGeometry geometry, const std::optional<std::vector<MotionTransform>>& motion);
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<RTCScene> instanced_;  // the moving primitives' own scenes
};

}  // namespace vesper
