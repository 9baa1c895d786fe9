#pragma once

namespace vesper {
inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;
inline constexpr float kPiOver2 = 1.57079632679489661923f;
inline constexpr float kPiOver4 = 0.78539816339744830961f;
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

constexpr float radians(float deg) { return deg * (kPi / 180.f); }
constexpr float sqr(float x) { return x * x; }
template <typename T>
constexpr T clamp(T v, T lo, T hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}
inline float safe_sqrt(float x) { return x > 0.f ? __builtin_sqrtf(x) : 0.f; }
// Power heuristic with beta = 2 (Veach).
inline float power_heuristic(float pdf_a, float pdf_b) {
  const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a + b > 0.f ? a / (a + b) : 0.f;
}
// pdf_a's share when three strategies make the same path.
inline float power_heuristic(float pdf_a, float pdf_b, float pdf_c) {
  const float a = pdf_a * pdf_a, s = a + pdf_b * pdf_b + pdf_c * pdf_c;
  return s > 0.f ? a / s : 0.f;
}
}  // namespace vesper
