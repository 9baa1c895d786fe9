#include "renderer/scene/light_builder.h"

#include <cmath>

namespace vesper {
namespace {

float cos_degrees(double degrees) { return float(std::cos(degrees * M_PI / 180.0)); }

RenderLight make(const QuadLightDesc& d, const RenderSpace& space) {
  QuadLight q;
  q.corner = space.point(d.corner);
  q.edge1 = space.vector(d.edge1);
  q.edge2 = space.vector(d.edge2);
  const Vec3 c = cross(q.edge1, q.edge2);
  q.area = length(c);
  q.normal = q.area > 0.f ? c / q.area : Vec3(0, 0, 1);
  q.radiance = d.radiance;
  return {q, AccelQuad{q.corner, q.edge1, q.edge2, 0, -1, -1, {}}};
}

RenderLight make(const PointLightDesc& d, const RenderSpace& space) {
  return {PointLight{space.point(d.position), d.intensity * space.intensity_scale(),
                     float(d.radius * space.inv_scale)},
          std::nullopt};
}

RenderLight make(const SpotLightDesc& d, const RenderSpace& space) {
  SpotLight sp;
  sp.position = space.point(d.position);
  sp.direction = normalize(Vec3(d.direction));
  sp.intensity = d.intensity * space.intensity_scale();
  sp.cos_cone = cos_degrees(d.cone_angle);
  sp.cos_falloff_start = cos_degrees(d.falloff_start);
  sp.radius = float(d.radius * space.inv_scale);
  return {sp, std::nullopt};
}

RenderLight make(const SunLightDesc& d, const RenderSpace&) {
  SunLight sun;
  sun.direction = normalize(Vec3(d.direction));
  sun.irradiance = d.irradiance;
  const double half = 0.5 * d.angle * M_PI / 180.0;
  sun.cos_max = half > 0 ? float(std::cos(half)) : 1.f;
  if (sun.cos_max >= 1.f) sun.cos_max = 1.f;
  sun.frame = Frame::from_normal(sun.direction);
  const double sin2 = std::sin(half) * std::sin(half);
  sun.radiance = sun.is_delta() ? Rgb{} : d.irradiance * float(1.0 / (M_PI * sin2));
  // A delta sun cannot be hit: only light sampling finds it.
  return {sun, std::nullopt, !sun.is_delta()};
}

RenderLight make(const EnvironmentLightDesc& d, const RenderSpace&) {
  EnvironmentLight env;
  const float scale = float(d.scale);
  if (d.image) {
    std::vector<Rgb> px = d.image->pixels;
    for (auto& c : px) c *= scale;
    env.map = EnvironmentLight::make_map(d.image->width, d.image->height, std::move(px));
  } else {
    env.constant = d.radiance * scale;
  }
  const double rot = d.rotation * M_PI / 180.0;
  env.cos_rot = float(std::cos(rot));
  env.sin_rot = float(std::sin(rot));
  return {std::move(env), std::nullopt, true};
}

}  // namespace

RenderLight make_render_light(const LightDesc& desc, const RenderSpace& space) {
  return std::visit([&](const auto& d) { return make(d, space); }, desc.light);
}

}  // namespace vesper
