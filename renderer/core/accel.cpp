#include "renderer/core/accel.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include "renderer/core/embree_scene.h"
#include "renderer/core/motion_steps.h"

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

// By Embree geometry id, in EmbreeScene's order: quads, spheres, meshes.
std::vector<GeomRecord> records_of(const AccelGeometry& g) {
  std::vector<GeomRecord> records;
  for (uint32_t i = 0; i < g.quads.size(); ++i) records.push_back({GeomKind::Quad, i});
  for (uint32_t i = 0; i < g.spheres.size(); ++i) records.push_back({GeomKind::Sphere, i});
  for (uint32_t i = 0; i < g.meshes.size(); ++i) records.push_back({GeomKind::Mesh, i});
  return records;
}

// A moving primitive's shape at `time`, interpolated as Embree does.
AccelQuad::Step quad_at(const AccelQuad& q, float time) {
  if (q.steps.empty()) return {q.corner, q.edge1, q.edge2};
  const auto [k, f] = step_position(q.steps.size(), time);
  const AccelQuad::Step &a = q.steps[k], &b = q.steps[k + 1];
  return {lerp_steps(a.corner, b.corner, f), lerp_steps(a.edge1, b.edge1, f),
          lerp_steps(a.edge2, b.edge2, f)};
}

AccelSphere::Step sphere_at(const AccelSphere& s, float time) {
  if (s.steps.empty()) return {s.center, s.radius};
  const auto [k, f] = step_position(s.steps.size(), time);
  const AccelSphere::Step &a = s.steps[k], &b = s.steps[k + 1];
  return {lerp_steps(a.center, b.center, f), lerp_steps(a.radius, b.radius, f)};
}

Vec3 vertex_at(const AccelMesh& m, uint32_t i, float time) {
  if (m.steps.empty()) return m.positions[i];
  const auto [k, f] = step_position(m.steps.size(), time);
  return lerp_steps(m.steps[k][i], m.steps[k + 1][i], f);
}

}  // namespace

struct Accel::Impl {
  AccelGeometry geometry;
  std::vector<GeomRecord> records;
  EmbreeScene embree;  // declared after `geometry`, whose mesh buffers it shares
  RTCScene scene;

  explicit Impl(AccelGeometry g)
      : geometry(without_degenerate(std::move(g))),
        records(records_of(geometry)),
        embree(geometry),
        scene(embree.scene()) {}
};

Accel::Accel(std::vector<AccelQuad> quads, std::vector<AccelSphere> spheres,
             std::vector<AccelMesh> meshes)
    : impl_(std::make_unique<Impl>(
          AccelGeometry{std::move(quads), std::move(spheres), std::move(meshes)})) {}

Accel::~Accel() = default;

size_t Accel::primitive_count() const { return impl_->geometry.primitive_count(); }

const AccelGeometry& Accel::geometry() const { return impl_->geometry; }

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
  rh.ray.time = ray.time;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

  // A moving primitive may be an instance (core/rigid_motion.h): its record
  // is at the instance's id, and primID is the instanced primitive's.
  const unsigned id =
      rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? rh.hit.instID[0] : rh.hit.geomID;
  const GeomRecord rec = impl_->records[id];
  SurfaceHit hit;
  hit.t = rh.ray.tfar;
  const float u = rh.hit.u, v = rh.hit.v;
  switch (rec.kind) {
    case GeomKind::Quad: {
      const AccelQuad& q = impl_->geometry.quads[rec.index];
      const AccelQuad::Step s = quad_at(q, ray.time);
      hit.p = s.corner + s.edge1 * u + s.edge2 * v;
      hit.n = normalize(cross(s.edge1, s.edge2));
      hit.material = q.material;
      hit.light = q.light;
      hit.shape = q.shape;
      break;
    }
    case GeomKind::Sphere: {
      const AccelSphere& sphere = impl_->geometry.spheres[rec.index];
      const AccelSphere::Step s = sphere_at(sphere, ray.time);
      const Vec3 d = ray.origin + ray.dir * hit.t - s.center;
      hit.n = normalize(d);
      hit.p = s.center + hit.n * s.radius;  // re-project onto the surface (pbrt)
      hit.material = sphere.material;
      hit.shape = sphere.shape;
      break;
    }
    case GeomKind::Mesh: {
      const AccelMesh& m = impl_->geometry.meshes[rec.index];
      const auto& tri = m.triangles[rh.hit.primID];
      const Vec3 p0 = vertex_at(m, tri[0], ray.time), p1 = vertex_at(m, tri[1], ray.time),
                 p2 = vertex_at(m, tri[2], ray.time);
      hit.p = p0 + (p1 - p0) * u + (p2 - p0) * v;
      hit.n = normalize(cross(p1 - p0, p2 - p0));
      hit.material = m.material;
      hit.shape = m.shape;
      break;
    }
  }
  if (!is_finite(hit.p) || !is_finite(hit.n)) return std::nullopt;
  return hit;
}

bool Accel::occluded(const Vec3& origin, const Vec3& dir, float tmax, float time) const {
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
  r.time = time;
  rtcOccluded1(impl_->scene, &ctx, &r);
  return r.tfar < 0.f;  // Embree sets tfar = -inf on a hit
}

}  // namespace vesper
