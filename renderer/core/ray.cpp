#include "renderer/core/ray.h"

#include <bit>
#include <cmath>
#include <cstdint>

namespace vesper {
namespace {
constexpr float kOrigin = 1.0f / 32.0f;
constexpr float kFloatScale = 1.0f / 65536.0f;
constexpr float kIntScale = 256.0f;

float offset_component(float p, float n) {
  const int32_t of = int32_t(kIntScale * n);
  const float pi = std::bit_cast<float>(std::bit_cast<int32_t>(p) + (p < 0 ? -of : of));
  return std::abs(p) < kOrigin ? p + kFloatScale * n : pi;
}
}  // namespace

Vec3 offset_ray_origin(const Vec3& p, const Vec3& n) {
  return {offset_component(p.x, n.x), offset_component(p.y, n.y), offset_component(p.z, n.z)};
}

}  // namespace vesper
