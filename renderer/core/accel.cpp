#include "renderer/core/accel.h"

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace vesper {

void set_flush_to_zero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

namespace {
enum class GeomKind : uint8_t { Quad, Sphere, Mesh };
struct GeomRecord {
  GeomKind kind;
  uint32_t index;  // into quads / spheres / meshes
};

void embree_error(void*, RTCError code, const char* msg) {
  // Called from inside Embree's C code: report, never throw through it.
  spdlog::error("Embree error {}: {}", int(code), msg ? msg : "");
}
}  // namespace

struct Accel::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<AccelQuad> quads;
  std::vector<AccelSphere> spheres;
  std::vector<AccelMesh> meshes;
  std::vector<GeomRecord> records;  // by Embree geometry id
  size_t primitives = 0;

  void attach(RTCGeometry g, GeomRecord rec) {
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    if (records.size() <= id) records.resize(id + 1);
    records[id] = rec;
  }
};

Accel::Accel(std::vector<AccelQuad> quads, std::vector<AccelSphere> spheres,
             std::vector<AccelMesh> meshes)
    : impl_(std::make_unique<Impl>()) {
  Impl& im = *impl_;
  im.quads = std::move(quads);
  im.spheres = std::move(spheres);
  im.meshes = std::move(meshes);
  im.device = rtcNewDevice("");
  if (!im.device) throw std::runtime_error("could not create an Embree device");
  rtcSetDeviceErrorFunction(im.device, embree_error, nullptr);
  im.scene = rtcNewScene(im.device);
  rtcSetSceneFlags(im.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(im.scene, RTC_BUILD_QUALITY_HIGH);

  for (uint32_t i = 0; i < im.quads.size(); ++i) {
    const AccelQuad& q = im.quads[i];
    if (!(length_squared(cross(q.edge1, q.edge2)) > 0.f)) continue;  // zero area: invisible
    RTCGeometry g = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_QUAD);
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
    im.attach(g, {GeomKind::Quad, i});
    ++im.primitives;
  }
  for (uint32_t i = 0; i < im.spheres.size(); ++i) {
    const AccelSphere& s = im.spheres[i];
    RTCGeometry g = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
    v[0] = s.center.x;
    v[1] = s.center.y;
    v[2] = s.center.z;
    v[3] = s.radius;
    im.attach(g, {GeomKind::Sphere, i});
    ++im.primitives;
  }
  for (uint32_t i = 0; i < im.meshes.size(); ++i) {
    AccelMesh& m = im.meshes[i];
    // Degenerate triangles can never be hit meaningfully and have no normal.
    std::erase_if(m.triangles, [&](const std::array<uint32_t, 3>& t) {
      const Vec3 c =
          cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
      return !(length_squared(c) > 0.f) || !is_finite(c);
    });
    if (m.triangles.empty()) continue;
    RTCGeometry g = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.positions.data(),
                               0, sizeof(Vec3), m.positions.size());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.triangles.data(), 0,
                               3 * sizeof(uint32_t), m.triangles.size());
    im.attach(g, {GeomKind::Mesh, i});
    im.primitives += m.triangles.size();
  }
  rtcCommitScene(im.scene);
}

Accel::~Accel() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

size_t Accel::primitive_count() const { return impl_->primitives; }

std::optional<SurfaceHit> Accel::intersect(const Ray& ray) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray.org_x = ray.origin.x;
  rh.ray.org_y = ray.origin.y;
  rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.dir.x;
  rh.ray.dir_y = ray.dir.y;
  rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = 0.f;
  rh.ray.tfar = ray.tmax;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.flags = 0;
  rh.ray.time = 0.f;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

  const GeomRecord rec = impl_->records[rh.hit.geomID];
  SurfaceHit hit;
  hit.t = rh.ray.tfar;
  const float u = rh.hit.u, v = rh.hit.v;
  switch (rec.kind) {
    case GeomKind::Quad: {
      const AccelQuad& q = impl_->quads[rec.index];
      hit.p = q.corner + q.edge1 * u + q.edge2 * v;
      hit.n = normalize(cross(q.edge1, q.edge2));
      hit.material = q.material;
      hit.light = q.light;
      break;
    }
    case GeomKind::Sphere: {
      const AccelSphere& s = impl_->spheres[rec.index];
      const Vec3 d = ray.origin + ray.dir * hit.t - s.center;
      hit.n = normalize(d);
      hit.p = s.center + hit.n * s.radius;  // re-project onto the surface (pbrt)
      hit.material = s.material;
      break;
    }
    case GeomKind::Mesh: {
      const AccelMesh& m = impl_->meshes[rec.index];
      const auto& tri = m.triangles[rh.hit.primID];
      const Vec3 &p0 = m.positions[tri[0]], &p1 = m.positions[tri[1]], &p2 = m.positions[tri[2]];
      hit.p = p0 + (p1 - p0) * u + (p2 - p0) * v;
      hit.n = normalize(cross(p1 - p0, p2 - p0));
      hit.material = m.material;
      break;
    }
  }
  if (!is_finite(hit.p) || !is_finite(hit.n)) return std::nullopt;
  return hit;
}

bool Accel::occluded(const Vec3& origin, const Vec3& dir, float tmax) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r;
  r.org_x = origin.x;
  r.org_y = origin.y;
  r.org_z = origin.z;
  r.dir_x = dir.x;
  r.dir_y = dir.y;
  r.dir_z = dir.z;
  r.tnear = 0.f;
  r.tfar = tmax;
  r.mask = 0xFFFFFFFFu;
  r.flags = 0;
  r.time = 0.f;
  rtcOccluded1(impl_->scene, &ctx, &r);
  return r.tfar < 0.f;  // Embree sets tfar = -inf on a hit
}

}  // namespace vesper
