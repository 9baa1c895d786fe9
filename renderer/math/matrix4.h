#pragma once
// Row-major 4x4 matrices of affine maps: the last row is always 0 0 0 1, so
// products and inverses only compute the upper 3x4 block.
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>

namespace vesper {

template <typename T>
struct Matrix4T {
  std::array<T, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

  constexpr T operator()(int row, int col) const { return m[size_t(row * 4 + col)]; }
  constexpr T& operator()(int row, int col) { return m[size_t(row * 4 + col)]; }
  constexpr bool is_affine() const {
    return m[12] == T(0) && m[13] == T(0) && m[14] == T(0) && m[15] == T(1);
  }
  // Every entry NaN: the inverse of a singular matrix (as pbrt-v4 does).
  static constexpr Matrix4T nan() {
    Matrix4T r;
    r.m.fill(std::numeric_limits<T>::quiet_NaN());
    return r;
  }
  template <typename U>
  constexpr Matrix4T<U> cast() const {
    Matrix4T<U> r;
    for (size_t i = 0; i < 16; ++i) r.m[i] = U(m[i]);
    return r;
  }
  friend constexpr bool operator==(const Matrix4T&, const Matrix4T&) = default;
};

using Matrix4 = Matrix4T<double>;

// (a * b)(p) = a(b(p)) for affine a and b. The translation column adds a's
// translation first: the order every transform in Vesper has been composed in.
template <typename T>
constexpr Matrix4T<T> operator*(const Matrix4T<T>& a, const Matrix4T<T>& b) {
  Matrix4T<T> r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      T v = j == 3 ? a(i, 3) : T(0);
      for (int k = 0; k < 3; ++k) v += a(i, k) * b(k, j);
      r(i, j) = v;
    }
  }
  return r;
}

// Inverse of an affine matrix from the cofactors of its 3x3 block; nullopt
// when the block is singular (|det| <= 1e-300) or not finite.
template <typename T>
std::optional<Matrix4T<T>> affine_inverse(const Matrix4T<T>& a) {
  const auto& m = a.m;
  const T c00 = m[5] * m[10] - m[6] * m[9], c01 = m[6] * m[8] - m[4] * m[10],
          c02 = m[4] * m[9] - m[5] * m[8];
  const T det = m[0] * c00 + m[1] * c01 + m[2] * c02;
  if (!(std::abs(double(det)) > 1e-300) || !std::isfinite(det)) return std::nullopt;
  const T id = T(1) / det;
  Matrix4T<T> r;
  // clang-format off
  r.m = {c00 * id, (m[2] * m[9] - m[1] * m[10]) * id, (m[1] * m[6] - m[2] * m[5]) * id, 0,
         c01 * id, (m[0] * m[10] - m[2] * m[8]) * id, (m[2] * m[4] - m[0] * m[6]) * id, 0,
         c02 * id, (m[1] * m[8] - m[0] * m[9]) * id,  (m[0] * m[5] - m[1] * m[4]) * id,  0,
         0,        0,                                 0,                                 1};
  // clang-format on
  for (int i = 0; i < 3; ++i) r(i, 3) = -(r(i, 0) * m[3] + r(i, 1) * m[7] + r(i, 2) * m[11]);
  return r;
}

}  // namespace vesper
