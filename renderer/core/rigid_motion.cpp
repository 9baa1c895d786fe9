#include "renderer/core/rigid_motion.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "renderer/math/matrix4.h"

namespace vesper {
namespace {

using Frame4 = std::array<Vec3d, 4>;  // an origin and three points spanning space

// The affine map taking from[i] to to[i] (i = 0..3), in double.
std::optional<Matrix4> affine_between(const Frame4& from, const Frame4& to) {
  Matrix4 a, b;
  for (int c = 0; c < 3; ++c) {
    const Vec3d u = from[size_t(c + 1)] - from[0], v = to[size_t(c + 1)] - to[0];
    for (int r = 0; r < 3; ++r) a(r, c) = u[r], b(r, c) = v[r];
  }
  for (int r = 0; r < 3; ++r) a(r, 3) = from[0][r], b(r, 3) = to[0][r];
  const auto inverse = affine_inverse(a);
  if (!inverse) return std::nullopt;
  const Matrix4 m = b * *inverse;
  for (double v : m.m)
    if (!std::isfinite(v)) return std::nullopt;
  return m;
}

MotionTransform to_embree(const Matrix4& m) {
  MotionTransform t;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) t[size_t(c * 3 + r)] = float(m(r, c));
  return t;
}

// A plane's three points plus one off it (along the normal, at the edges' scale).
Frame4 plane_frame(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2) {
  const Vec3d n = cross(p1 - p0, p2 - p0);
  return {p0, p1, p2, p0 + n / std::sqrt(length(n))};
}

template <typename FrameAt>
std::optional<std::vector<MotionTransform>> transforms(size_t steps, FrameAt frame_at) {
  if (steps < 2) return std::nullopt;
  const Frame4 first = frame_at(0);
  std::vector<MotionTransform> out;
  for (size_t k = 0; k < steps; ++k) {
    const auto m = affine_between(first, frame_at(k));
    if (!m || !affine_inverse(*m)) return std::nullopt;
    out.push_back(to_embree(*m));
  }
  return out;
}

Vec3d d(const Vec3& v) { return Vec3d(v.x, v.y, v.z); }

// Four vertex indices of step 0 spanning it as well as the mesh allows: the
// first vertex, the farthest from it, the farthest from their line, the
// farthest from their plane (-1 when the mesh is flat).
std::array<int64_t, 4> spanning_vertices(const std::vector<Vec3>& p) {
  auto farthest = [&](auto distance) {
    size_t best = 0;
    double best_d = -1;
    for (size_t i = 0; i < p.size(); ++i)
      if (const double v = distance(d(p[i])); v > best_d) best = i, best_d = v;
    return std::pair{int64_t(best), best_d};
  };
  const Vec3d a = d(p[0]);
  const auto [i1, d1] = farthest([&](const Vec3d& x) { return length(x - a); });
  const Vec3d b = d(p[size_t(i1)]);
  const auto [i2, d2] = farthest([&](const Vec3d& x) { return length(cross(x - a, b - a)); });
  const Vec3d n = normalize(cross(d(p[size_t(i2)]) - a, b - a));
  const auto [i3, d3] = farthest([&](const Vec3d& x) { return std::abs(dot(x - a, n)); });
  return {0, i1, i2, d3 > 1e-4 * d1 ? i3 : -1};
}

// Whether m takes every vertex of step 0 to step k within float rounding.
bool maps_all(const MotionTransform& m, const std::vector<Vec3>& from,
              const std::vector<Vec3>& to) {
  for (size_t i = 0; i < from.size(); ++i) {
    const Vec3d p = d(from[i]), q = d(to[i]);
    double err = 0, scale = 0;
    for (int r = 0; r < 3; ++r) {
      const double v =
          m[size_t(r)] * p.x + m[size_t(3 + r)] * p.y + m[size_t(6 + r)] * p.z + m[size_t(9 + r)];
      err = std::max(err, std::abs(v - q[r]));
      scale = std::max({scale, std::abs(q[r]), std::abs(p[r])});
    }
    if (err > 64 * FLT_EPSILON * scale) return false;
  }
  return true;
}

}  // namespace

std::optional<std::vector<MotionTransform>> rigid_motion(const AccelQuad& q) {
  return transforms(q.steps.size(), [&](size_t k) {
    const AccelQuad::Step& s = q.steps[k];
    return plane_frame(d(s.corner), d(s.corner + s.edge1), d(s.corner + s.edge2));
  });
}

std::optional<std::vector<MotionTransform>> rigid_motion(const AccelSphere& sphere) {
  return transforms(sphere.steps.size(), [&](size_t k) {
    const AccelSphere::Step& s = sphere.steps[k];
    const Vec3d c = d(s.center);
    const double r = s.radius;
    return Frame4{c, c + Vec3d(r, 0, 0), c + Vec3d(0, r, 0), c + Vec3d(0, 0, r)};
  });
}

std::optional<std::vector<MotionTransform>> rigid_motion(const AccelMesh& m) {
  if (m.steps.size() < 2 || m.steps[0].empty()) return std::nullopt;
  const std::array<int64_t, 4> idx = spanning_vertices(m.steps[0]);
  auto out = transforms(m.steps.size(), [&](size_t k) {
    const std::vector<Vec3>& p = m.steps[k];
    const Vec3d a = d(p[size_t(idx[0])]), b = d(p[size_t(idx[1])]), c = d(p[size_t(idx[2])]);
    return idx[3] < 0 ? plane_frame(a, b, c) : Frame4{a, b, c, d(p[size_t(idx[3])])};
  });
  if (!out) return std::nullopt;
  for (size_t k = 1; k < m.steps.size(); ++k)
    if (!maps_all((*out)[k], m.steps[0], m.steps[k])) return std::nullopt;
  return out;
}

}  // namespace vesper
