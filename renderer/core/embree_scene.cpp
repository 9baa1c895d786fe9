#include "renderer/core/embree_scene.h"

#include <spdlog/spdlog.h>

#include <stdexcept>

namespace vesper {
namespace {

void embree_error(void*, RTCError code, const char* msg) {
  // Called from inside Embree's C code: report, never throw through it.
  spdlog::error("Embree error {}: {}", int(code), msg ? msg : "");
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
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4));
    const Vec3 p[4] = {q.corner, q.corner + q.edge1, q.corner + q.edge1 + q.edge2,
                       q.corner + q.edge2};
    for (int k = 0; k < 4; ++k) {
      v[3 * k] = p[k].x;
      v[3 * k + 1] = p[k].y;
      v[3 * k + 2] = p[k].z;
    }
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), 1));
    for (unsigned k = 0; k < 4; ++k) idx[k] = k;
    attach(g);
  }
  for (const AccelSphere& s : geometry.spheres) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
    v[0] = s.center.x;
    v[1] = s.center.y;
    v[2] = s.center.z;
    v[3] = s.radius;
    attach(g);
  }
  for (const AccelMesh& m : geometry.meshes) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.positions.data(),
                               0, sizeof(Vec3), m.positions.size());
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
