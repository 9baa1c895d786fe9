#pragma once
// An Embree scene (robust, high build quality) on its own device, built from
// render-space geometry: the BVH that vesper::Accel queries, and the one the
// ray-throughput benchmark traces raw rays against. The only header that
// exposes Embree (core/accel.h keeps it hidden from the rest of the renderer).
#include <embree3/rtcore.h>

#include "renderer/core/accel_geometry.h"

namespace vesper {

class EmbreeScene {
 public:
  // Geometry ids, in order: geometry.quads, then spheres, then meshes. The
  // meshes' vertex and index buffers are shared, not copied: `geometry` must
  // outlive the scene and hold no degenerate primitives (without_degenerate).
  explicit EmbreeScene(const AccelGeometry& geometry);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene scene() const { return scene_; }

 private:
  void attach(RTCGeometry geometry);
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace vesper
