#pragma once
// Small fixed-size vectors. Vec3 is the renderer's float vector; Vec3d holds
// scene-description values before they are made camera-relative.
#include <algorithm>
#include <cmath>

namespace vesper {

template <typename T>
struct Vec3T {
  T x = 0, y = 0, z = 0;
  constexpr Vec3T() = default;
  constexpr Vec3T(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit Vec3T(T v) : x(v), y(v), z(v) {}
  template <typename U>
  constexpr explicit Vec3T(const Vec3T<U>& o) : x(T(o.x)), y(T(o.y)), z(T(o.z)) {}

  constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3T operator-() const { return {-x, -y, -z}; }
  constexpr Vec3T& operator+=(const Vec3T& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  constexpr Vec3T& operator-=(const Vec3T& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  constexpr Vec3T& operator*=(T s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  friend constexpr Vec3T operator+(Vec3T a, const Vec3T& b) { return a += b; }
  friend constexpr Vec3T operator-(Vec3T a, const Vec3T& b) { return a -= b; }
  friend constexpr Vec3T operator*(Vec3T a, T s) { return a *= s; }
  friend constexpr Vec3T operator*(T s, Vec3T a) { return a *= s; }
  friend constexpr Vec3T operator/(Vec3T a, T s) { return a *= (T(1) / s); }
  friend constexpr bool operator==(const Vec3T&, const Vec3T&) = default;
};

using Vec3 = Vec3T<float>;
using Vec3d = Vec3T<double>;

struct Vec2 {
  float x = 0, y = 0;
};

template <typename T>
constexpr T dot(const Vec3T<T>& a, const Vec3T<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
constexpr Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
constexpr Vec3T<T> mul(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <typename T>
inline T length_squared(const Vec3T<T>& a) {
  return dot(a, a);
}
template <typename T>
inline T length(const Vec3T<T>& a) {
  return std::sqrt(dot(a, a));
}
template <typename T>
inline Vec3T<T> normalize(const Vec3T<T>& a) {
  return a / length(a);
}
template <typename T>
inline T max_abs_component(const Vec3T<T>& a) {
  return std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)});
}
template <typename T>
inline bool is_finite(const Vec3T<T>& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
template <typename T>
inline Vec3T<T> abs(const Vec3T<T>& a) {
  return {std::abs(a.x), std::abs(a.y), std::abs(a.z)};
}
template <typename T>
inline Vec3T<T> min(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <typename T>
inline Vec3T<T> max(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
// Reflects w about n (both pointing away from the surface).
inline Vec3 reflect(const Vec3& w, const Vec3& n) { return -w + 2.f * dot(w, n) * n; }

}  // namespace vesper
