#pragma once
// The closed set of lights behind one interface (light_interface.h). Every
// operation is one std::visit calling the same method on whichever type is
// held: no per-type branch here or in the integrator.
#include <optional>
#include <utility>
#include <variant>

#include "renderer/lights/environment_light.h"
#include "renderer/lights/light_interface.h"
#include "renderer/lights/point_light.h"
#include "renderer/lights/quad_light.h"
#include "renderer/lights/spot_light.h"
#include "renderer/lights/sun_light.h"

namespace vesper {

// A light type, checked against the interface: a type that does not satisfy
// it fails to compile here, with the requirement it misses in the message.
template <typename T>
struct CheckedLightType {
  static_assert(LightInterface<T>, "every light type implements light_interface.h");
  using type = T;
};

template <typename... Types>
using LightVariant = std::variant<typename CheckedLightType<Types>::type...>;

// The closed set of light types.
using LightTypes = LightVariant<QuadLight, PointLight, SpotLight, SunLight, EnvironmentLight>;

template <typename T>
concept OneOfTheLightTypes = std::constructible_from<LightTypes, T>;

class Light {
 public:
  // Implicit: any of the light types converts to a Light.
  template <OneOfTheLightTypes T>
  Light(T&& light) : light_(std::forward<T>(light)) {}

  std::optional<LightSample> sample(const Vec3& p, Vec2 u) const {
    return std::visit([&](const auto& l) { return l.sample(p, u); }, light_);
  }
  float pdf(const Vec3& wi, float distance) const {
    return std::visit([&](const auto& l) { return l.pdf(wi, distance); }, light_);
  }
  Rgb emitted(const Vec3& wi) const {
    return std::visit([&](const auto& l) { return l.emitted(wi); }, light_);
  }
  Rgb intensity_toward(const Vec3& w_from_light) const {
    return std::visit([&](const auto& l) { return l.intensity_toward(w_from_light); }, light_);
  }
  float power(float scene_radius) const {
    return std::visit([&](const auto& l) { return l.power(scene_radius); }, light_);
  }
  std::optional<LightBounds> bounds() const {
    return std::visit([](const auto& l) { return l.bounds(); }, light_);
  }
  // A light at infinity in one direction (or a small cone of them): sun
  // shafts sample distances toward it (sun_shaft.h).
  bool is_sun() const { return std::holds_alternative<SunLight>(light_); }
  bool is_delta_sun() const {
    const auto* sun = std::get_if<SunLight>(&light_);
    return sun && sun->is_delta();
  }

 private:
  LightTypes light_;
};

}  // namespace vesper
