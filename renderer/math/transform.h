#pragma once
// An affine transform with its inverse (as pbrt-v4's Transform): scene
// placements and grid index -> world maps in double (`Transform`), render
// space -> grid index maps in float (`Transformf`, media lookups per sample).
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "renderer/math/matrix4.h"
#include "renderer/math/vec.h"

namespace vesper {

template <typename T>
class TransformT {
 public:
  TransformT() = default;  // identity
  // `m` must be affine (last row 0 0 0 1). A singular m gives a NaN inverse
  // (check invertible()).
  explicit TransformT(const Matrix4T<T>& m)
      : m_(m), inv_(affine_inverse(m).value_or(Matrix4T<T>::nan())) {
    if (!m.is_affine()) throw std::invalid_argument("Transform: the last row must be 0 0 0 1");
  }

  static TransformT translate(const Vec3T<T>& t) {
    Matrix4T<T> m;
    m(0, 3) = t.x, m(1, 3) = t.y, m(2, 3) = t.z;
    return TransformT(m);
  }
  static TransformT scale(const Vec3T<T>& s) {
    Matrix4T<T> m;
    m(0, 0) = s.x, m(1, 1) = s.y, m(2, 2) = s.z;
    return TransformT(m);
  }
  // Right-handed rotation about a unit axis (Rodrigues): counter-clockwise
  // when the axis points toward the viewer.
  static TransformT rotate(const Vec3T<T>& axis, T degrees) {
    const T a = degrees * std::numbers::pi_v<T> / T(180);
    const T c = std::cos(a), s = std::sin(a), t = 1 - c;
    const T x = axis.x, y = axis.y, z = axis.z;
    Matrix4T<T> m;
    // clang-format off
    m.m = {t * x * x + c,     t * x * y - s * z, t * x * z + s * y, 0,
           t * x * y + s * z, t * y * y + c,     t * y * z - s * x, 0,
           t * x * z - s * y, t * y * z + s * x, t * z * z + c,     0,
           0,                 0,                 0,                 1};
    // clang-format on
    return TransformT(m);
  }

  const Matrix4T<T>& matrix() const { return m_; }
  const Matrix4T<T>& inverse_matrix() const { return inv_; }
  bool invertible() const { return !std::isnan(inv_(0, 0)); }

  Vec3T<T> apply_point(const Vec3T<T>& p) const {
    const auto& m = m_.m;
    return {m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3],
            m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
            m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]};
  }
  Vec3T<T> apply_vector(const Vec3T<T>& v) const {
    const auto& m = m_.m;
    return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[4] * v.x + m[5] * v.y + m[6] * v.z,
            m[8] * v.x + m[9] * v.y + m[10] * v.z};
  }
  // Normals go through the inverse transpose, so they stay perpendicular to
  // transformed surfaces under non-uniform scale. Not normalized.
  Vec3T<T> apply_normal(const Vec3T<T>& n) const {
    const auto& i = inv_.m;
    return {i[0] * n.x + i[4] * n.y + i[8] * n.z, i[1] * n.x + i[5] * n.y + i[9] * n.z,
            i[2] * n.x + i[6] * n.y + i[10] * n.z};
  }

  template <typename U>
  TransformT<U> cast() const {
    return TransformT<U>(m_.template cast<U>(), inv_.template cast<U>());
  }

  // (a * b) applies b, then a. The inverse is recomputed from the product
  // (not inv(b) * inv(a)), so that it does not depend on how a transform was built.
  friend TransformT operator*(const TransformT& a, const TransformT& b) {
    return TransformT(a.m_ * b.m_);
  }
  friend TransformT inverse(const TransformT& t) { return TransformT(t.inv_, t.m_); }
  friend bool operator==(const TransformT&, const TransformT&) = default;

 private:
  template <typename>
  friend class TransformT;
  TransformT(const Matrix4T<T>& m, const Matrix4T<T>& inv) : m_(m), inv_(inv) {}

  Matrix4T<T> m_, inv_;
};

using Transform = TransformT<double>;
using Transformf = TransformT<float>;

}  // namespace vesper
