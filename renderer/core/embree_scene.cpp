#include "renderer/core/embree_scene.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

namespace vesper {
namespace {

void embree_error(void*, RTCError code, const char* msg) {
  // Called from inside Embree's C code: report, never throw through it.
  spdlog::error("Embree error {}: {}", int(code), msg ? msg : "");
}

// Vertex buffer `slot` of a quad geometry: the parallelogram's 4 corners.
void set_quad_vertices(RTCGeometry g, unsigned slot, const Vec3& corner, const Vec3& e1,
                       const Vec3& e2) {
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, slot,
                                                        RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4));
  const Vec3 p[4] = {corner, corner + e1, corner + e1 + e2, corner + e2};
  for (int k = 0; k < 4; ++k) {
    v[3 * k] = p[k].x;
    v[3 * k + 1] = p[k].y;
    v[3 * k + 2] = p[k].z;
  }
}

void set_sphere_vertex(RTCGeometry g, unsigned slot, const Vec3& center, float radius) {
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, slot,
                                                        RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
  v[0] = center.x;
  v[1] = center.y;
  v[2] = center.z;
  v[3] = radius;
}

// A moving primitive holds all its steps (vertex motion blur) when
// `motion` is null; with rigid motion only step 0 (an instance moves it).
// A still one holds its shape.
template <typename Prim>
bool vertex_steps(const Prim& p, const std::optional<std::vector<MotionTransform>>& motion) {
  return !p.steps.empty() && !motion;
}

RTCScene new_scene(RTCDevice device) {
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  return scene;
}

RTCGeometry new_quad(RTCDevice device, const AccelQuad& q, bool all_steps) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
  if (q.steps.empty()) set_quad_vertices(g, 0, q.corner, q.edge1, q.edge2);
  const size_t steps = all_steps ? q.steps.size() : std::min<size_t>(q.steps.size(), 1);
  if (all_steps) rtcSetGeometryTimeStepCount(g, unsigned(steps));
  for (size_t k = 0; k < steps; ++k)
    set_quad_vertices(g, unsigned(k), q.steps[k].corner, q.steps[k].edge1, q.steps[k].edge2);
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), 1));
  for (unsigned k = 0; k < 4; ++k) idx[k] = k;
  return g;
}

RTCGeometry new_sphere(RTCDevice device, const AccelSphere& s, bool all_steps) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  if (s.steps.empty()) set_sphere_vertex(g, 0, s.center, s.radius);
  const size_t steps = all_steps ? s.steps.size() : std::min<size_t>(s.steps.size(), 1);
  if (all_steps) rtcSetGeometryTimeStepCount(g, unsigned(steps));
  for (size_t k = 0; k < steps; ++k)
    set_sphere_vertex(g, unsigned(k), s.steps[k].center, s.steps[k].radius);
  return g;
}

RTCGeometry new_mesh(RTCDevice device, const AccelMesh& m, bool all_steps) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (m.steps.empty())
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.positions.data(),
                               0, sizeof(Vec3), m.positions.size());
  const size_t steps = all_steps ? m.steps.size() : std::min<size_t>(m.steps.size(), 1);
  if (all_steps) rtcSetGeometryTimeStepCount(g, unsigned(steps));
  for (size_t k = 0; k < steps; ++k)
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, unsigned(k), RTC_FORMAT_FLOAT3,
                               m.steps[k].data(), 0, sizeof(Vec3), m.steps[k].size());
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.triangles.data(), 0,
                             3 * sizeof(uint32_t), m.triangles.size());
  return g;
}

}  // namespace

EmbreeScene::EmbreeScene(const AccelGeometry& geometry) {
  device_ = rtcNewDevice("");
  if (!device_) throw std::runtime_error("could not create an Embree device");
  rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
  scene_ = new_scene(device_);
  // Geometry ids follow this order (Accel's records rely on it).
  for (const AccelQuad& q : geometry.quads) {
    const auto motion = rigid_motion(q);
    attach(new_quad(device_, q, vertex_steps(q, motion)), motion);
  }
  for (const AccelSphere& s : geometry.spheres) {
    const auto motion = rigid_motion(s);
    attach(new_sphere(device_, s, vertex_steps(s, motion)), motion);
  }
  for (const AccelMesh& m : geometry.meshes) {
    const auto motion = rigid_motion(m);
    attach(new_mesh(device_, m, vertex_steps(m, motion)), motion);
  }
  rtcCommitScene(scene_);
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  for (RTCScene s : instanced_) rtcReleaseScene(s);
  if (device_) rtcReleaseDevice(device_);
}

void EmbreeScene::attach(RTCGeometry geometry,
                         const std::optional<std::vector<MotionTransform>>& motion) {
  rtcCommitGeometry(geometry);
  if (!motion) {
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    return;
  }
  // A static scene of the primitive's step 0, instanced through its motion.
  RTCScene inner = new_scene(device_);
  rtcAttachGeometry(inner, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(inner);
  instanced_.push_back(inner);
  RTCGeometry instance = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(instance, inner);
  rtcSetGeometryTimeStepCount(instance, unsigned(motion->size()));
  for (size_t k = 0; k < motion->size(); ++k)
    rtcSetGeometryTransform(instance, unsigned(k), RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR,
                            (*motion)[k].data());
  rtcCommitGeometry(instance);
  rtcAttachGeometry(scene_, instance);
  rtcReleaseGeometry(instance);
}

}  // namespace vesper
