#pragma once
// Environment light: radiance arriving from infinitely far away in every
// direction, a constant or a lat-long image importance-sampled by luminance
// x sin(theta). Mapping (docs/scene-format.md#environment-images): for
// (u, v) in [0,1]^2, theta = v*pi from +Y, phi = 2*pi*u,
// dir = (sin(theta) sin(phi), cos(theta), -sin(theta) cos(phi)), then rotated
// by `rotation` about +Y.
//
// Scene keys ("type": "environment", docs/scene-format.md#lights); either
// `radiance` or `file`, not both; at most one environment light per scene:
//   radiance  rgb >= 0, W/(sr m^2)   constant radiance
//   file      string (path)          lat-long image, linear RGB, any format OIIO reads
//   scale     number >= 0            default 1, multiplies the image (`file` only)
//   rotation  degrees                default 0, about +Y, counter-clockwise seen from above
//                                    (`file` only)
//   group     string                 optional, light group for layers
// Radiance is invariant under the unit scale.
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "renderer/lights/light_interface.h"
#include "renderer/math/constants.h"
#include "renderer/sampling/distribution.h"
#include "renderer/sampling/warp.h"

namespace vesper {

struct EnvironmentMap {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;  // already multiplied by scale
  Distribution2D distribution;
};

struct EnvironmentLight {
  Rgb constant;  // used when map is null
  std::shared_ptr<const EnvironmentMap> map;
  float cos_rot = 1.f, sin_rot = 0.f;  // rotation about +Y

  static Vec3 uv_to_local_dir(Vec2 uv) {
    const float theta = uv.y * kPi, phi = 2.f * kPi * uv.x;
    const float st = std::sin(theta);
    return {st * std::sin(phi), std::cos(theta), -st * std::cos(phi)};
  }
  static Vec2 local_dir_to_uv(const Vec3& d) {
    // atan2 rather than acos(y): acos loses all precision near the poles.
    const float theta = std::atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y);
    float phi = std::atan2(d.x, -d.z);
    if (phi < 0.f) phi += 2.f * kPi;
    return {clamp(phi * kInv2Pi, 0.f, kOneMinusEpsilon),
            clamp(theta * kInvPi, 0.f, kOneMinusEpsilon)};
  }
  Vec3 to_world(const Vec3& d) const {
    return {cos_rot * d.x + sin_rot * d.z, d.y, -sin_rot * d.x + cos_rot * d.z};
  }
  Vec3 to_local(const Vec3& d) const {
    return {cos_rot * d.x - sin_rot * d.z, d.y, sin_rot * d.x + cos_rot * d.z};
  }

  Rgb intensity_toward(const Vec3& /*w_from_light*/) const { return {}; }
  Rgb emitted(const Vec3& wi) const {
    if (!map) return constant;
    const Vec2 uv = local_dir_to_uv(to_local(wi));
    const int x = std::min(int(uv.x * float(map->width)), map->width - 1);
    const int y = std::min(int(uv.y * float(map->height)), map->height - 1);
    return map->pixels[size_t(y) * size_t(map->width) + size_t(x)];
  }

  std::optional<LightSample> sample(const Vec3& /*p*/, Vec2 u) const {
    constexpr float inf = std::numeric_limits<float>::infinity();
    if (!map) {
      const Vec3 wi = sample_uniform_sphere(u);
      return LightSample{constant, wi, inf, kInv4Pi, false};
    }
    float pdf_uv = 0.f;
    const Vec2 uv = map->distribution.sample(u, &pdf_uv);
    const float sin_theta = std::sin(uv.y * kPi);
    if (pdf_uv <= 0.f || sin_theta <= 0.f) return std::nullopt;
    const Vec3 wi = to_world(uv_to_local_dir(uv));
    return LightSample{emitted(wi), wi, inf, pdf_uv / (2.f * kPi * kPi * sin_theta), false};
  }
  float pdf(const Vec3& wi, float /*distance*/) const {
    if (!map) return kInv4Pi;
    const Vec3 d = to_local(wi);
    const Vec2 uv = local_dir_to_uv(d);
    const float sin_theta = std::sqrt(d.x * d.x + d.z * d.z);
    if (sin_theta <= 0.f) return 0.f;
    return map->distribution.pdf(uv) / (2.f * kPi * kPi * sin_theta);
  }
  // What crosses the scene's bounding sphere.
  float power(float scene_radius) const {
    float avg = constant.average();
    if (map) {
      double sum = 0;
      for (int y = 0; y < map->height; ++y) {
        const double st = std::sin((y + 0.5) / map->height * kPi);
        for (int x = 0; x < map->width; ++x)
          sum += st * map->pixels[size_t(y) * map->width + x].average();
      }
      avg = float(sum / (double(map->width) * map->height) * kPi / 2.0);
    }
    return 4.f * kPi * kPi * sqr(scene_radius) * avg;
  }
  std::optional<LightBounds> bounds() const { return std::nullopt; }

  // Builds the sampling distribution: luminance x sin(theta) per texel.
  static std::shared_ptr<EnvironmentMap> make_map(int width, int height, std::vector<Rgb> pixels) {
    auto m = std::make_shared<EnvironmentMap>();
    m->width = width;
    m->height = height;
    m->pixels = std::move(pixels);
    std::vector<float> w(m->pixels.size());
    for (int y = 0; y < height; ++y) {
      const float st = std::sin((float(y) + 0.5f) / float(height) * kPi);
      for (int x = 0; x < width; ++x) {
        const size_t i = size_t(y) * size_t(width) + size_t(x);
        w[i] = std::max(m->pixels[i].max_component(), 0.f) * st;
      }
    }
    m->distribution = Distribution2D(w, width, height);
    return m;
  }
};

}  // namespace vesper
