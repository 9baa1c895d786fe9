#include "renderer/integrator/light_guide.h"

#include <algorithm>
#include <cmath>

#include "renderer/math/constants.h"
#include "renderer/math/frame.h"

namespace vesper {
namespace {

// Closer than this (relative to the light's own size) the guide stops
// sharpening: inside a sphere light or on a point light.
constexpr float kMinDistance2 = 1e-8f;

}  // namespace

LightGuide::LightGuide(const LightSampler& lights, const Vec3& p) : lights_(lights), p_(p) {
  for (size_t i = 0; i < lights.bounds().size(); ++i) total_ += weight(i);
}

float LightGuide::weight(size_t i) const {
  const std::optional<LightBounds>& b = lights_.bounds()[i];
  if (!b) return 0.f;
  const std::optional<Vec3> aim = b->aim();
  if (!aim || !(lights_.powers()[i] > 0.f)) return 0.f;
  const float radius2 = 0.25f * length_squared(b->hi - b->lo);
  const float d2 = std::max({length_squared(*aim - p_), radius2, kMinDistance2});
  return lights_.powers()[i] / d2;
}

std::optional<Vec3> LightGuide::sample(float u_light, Vec2 u) const {
  if (empty()) return std::nullopt;
  const float target = u_light * total_;
  float cum = 0.f;
  size_t chosen = lights_.bounds().size();
  for (size_t i = 0; i < lights_.bounds().size(); ++i) {
    const float w = weight(i);
    if (!(w > 0.f)) continue;
    chosen = i;
    if (target < cum + w) break;
    cum += w;
  }
  const Vec3 to_light = *lights_.bounds()[chosen]->aim() - p_;
  if (!(length_squared(to_light) > 0.f)) return std::nullopt;
  const float theta = kPi * u.x, phi = 2.f * kPi * u.y;
  const float sin_t = std::sin(theta);
  const Frame frame = Frame::from_normal(normalize(to_light));
  return normalize(
      frame.to_world({sin_t * std::cos(phi), sin_t * std::sin(phi), std::cos(theta)}));
}

float LightGuide::pdf(const Vec3& wi) const {
  if (empty()) return 0.f;
  double sum = 0;
  for (size_t i = 0; i < lights_.bounds().size(); ++i) {
    const float w = weight(i);
    if (!(w > 0.f)) continue;
    const Vec3 to_light = *lights_.bounds()[i]->aim() - p_;
    if (!(length_squared(to_light) > 0.f)) continue;
    const float cos_t = std::clamp(dot(wi, normalize(to_light)), -1.f, 1.f);
    // Bounded at the singular direction: the density stays finite (and MIS
    // weights defined) for a ray aimed exactly at the light.
    const float sin_t = std::max(1e-6f, std::sqrt(std::max(0.f, 1.f - cos_t * cos_t)));
    sum += double(w) / (2.0 * double(kPi) * double(kPi) * double(sin_t));
  }
  return float(sum / double(total_));
}

}  // namespace vesper
