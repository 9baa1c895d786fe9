#include "renderer/core/embree_scene.h"

#include <spdlog/spdlog.h>

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

// A moving primitive: one vertex buffer per time step (Embree motion blur).
void set_time_steps(RTCGeometry g, size_t steps) {
  if (steps > 0) rtcSetGeometryTimeStepCount(g, unsigned(steps));
}

}  // namespace

EmbreeScene::EmbreeScene(const AccelGeometry& geometry) {
  device_ = rtcNewDevice("");
  if (!device_) throw std::runtime_error("could not create an Embree device");
  rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

  for (const AccelQuad& q : geometry.quads) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_QUAD);
    set_time_steps(g, q.steps.size());
    if (q.steps.empty()) set_quad_vertices(g, 0, q.corner, q.edge1, q.edge2);
    for (size_t k = 0; k < q.steps.size(); ++k)
      set_quad_vertices(g, unsigned(k), q.steps[k].corner, q.steps[k].edge1, q.steps[k].edge2);
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), 1));
    for (unsigned k = 0; k < 4; ++k) idx[k] = k;
    attach(g);
  }
  for (const AccelSphere& s : geometry.spheres) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    set_time_steps(g, s.steps.size());
    if (s.steps.empty()) set_sphere_vertex(g, 0, s.center, s.radius);
    for (size_t k = 0; k < s.steps.size(); ++k)
      set_sphere_vertex(g, unsigned(k), s.steps[k].center, s.steps[k].radius);
    attach(g);
  }
  for (const AccelMesh& m : geometry.meshes) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    set_time_steps(g, m.steps.size());
    if (m.steps.empty())
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                 m.positions.data(), 0, sizeof(Vec3), m.positions.size());
    for (size_t k = 0; k < m.steps.size(); ++k)
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, unsigned(k), RTC_FORMAT_FLOAT3,
                                 m.steps[k].data(), 0, sizeof(Vec3), m.steps[k].size());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.triangles.data(), 0,
                               3 * sizeof(uint32_t), m.triangles.size());
    attach(g);
  }
  rtcCommitScene(scene_);
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

void EmbreeScene::attach(RTCGeometry geometry) {
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
}

}  // namespace vesper
