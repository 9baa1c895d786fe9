#pragma once
// Linear Rec.709 RGB radiance (scene-referred). Distinct from Vec3 so that
// colours and directions cannot be mixed up.
#include <algorithm>
#include <cmath>

namespace vesper {

struct Rgb {
  float r = 0, g = 0, b = 0;
  constexpr Rgb() = default;
  constexpr Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
  constexpr explicit Rgb(float v) : r(v), g(v), b(v) {}

  constexpr float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
  constexpr float& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
  constexpr Rgb& operator+=(const Rgb& o) {
    r += o.r;
    g += o.g;
    b += o.b;
    return *this;
  }
  constexpr Rgb& operator-=(const Rgb& o) {
    r -= o.r;
    g -= o.g;
    b -= o.b;
    return *this;
  }
  constexpr Rgb& operator*=(const Rgb& o) {
    r *= o.r;
    g *= o.g;
    b *= o.b;
    return *this;
  }
  constexpr Rgb& operator*=(float s) {
    r *= s;
    g *= s;
    b *= s;
    return *this;
  }
  friend constexpr Rgb operator+(Rgb a, const Rgb& o) { return a += o; }
  friend constexpr Rgb operator-(Rgb a, const Rgb& o) { return a -= o; }
  friend constexpr Rgb operator*(Rgb a, const Rgb& o) { return a *= o; }
  friend constexpr Rgb operator*(Rgb a, float s) { return a *= s; }
  friend constexpr Rgb operator*(float s, Rgb a) { return a *= s; }
  friend constexpr Rgb operator/(Rgb a, float s) { return a *= (1.f / s); }
  friend constexpr Rgb operator/(const Rgb& a, const Rgb& o) {
    return {a.r / o.r, a.g / o.g, a.b / o.b};
  }
  friend constexpr bool operator==(const Rgb&, const Rgb&) = default;

  constexpr bool is_black() const { return r == 0 && g == 0 && b == 0; }
  constexpr float max_component() const { return std::max(r, std::max(g, b)); }
  constexpr float average() const { return (r + g + b) / 3.f; }
  // Rec.709 / sRGB luminance weights.
  constexpr float luminance() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
  bool is_finite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

inline Rgb sqrt(const Rgb& c) { return {std::sqrt(c.r), std::sqrt(c.g), std::sqrt(c.b)}; }
inline Rgb lerp(float t, const Rgb& a, const Rgb& b) { return (1.f - t) * a + t * b; }

}  // namespace vesper
