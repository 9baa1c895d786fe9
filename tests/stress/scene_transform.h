#pragma once
// A scene moved and resized as a whole: p -> p * scale + offset for
// everything positional. Lights and media are adjusted so that the image does
// not change: point/spot intensities by scale^2 (same irradiance at the
// scaled distance), medium coefficients by 1/scale (same optical depth).
#include <type_traits>
#include <variant>

#include "renderer/scene/scene_description.h"

namespace vesper::test {

inline SceneDescription transformed(SceneDescription d, double scale, Vec3d offset) {
  auto pt = [&](Vec3d& p) { p = p * scale + offset; };
  auto vec = [&](Vec3d& v) { v = v * scale; };
  pt(d.camera.from);
  pt(d.camera.to);
  d.camera.focus_distance *= scale;
  for (auto& s : d.shapes)
    std::visit(
        [&](auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, QuadShapeDesc>) {
            pt(g.corner);
            vec(g.edge1);
            vec(g.edge2);
          } else if constexpr (std::is_same_v<T, SphereShapeDesc>) {
            pt(g.center);
            g.radius *= scale;
          } else {
            for (auto& p : g.positions) pt(p);
          }
        },
        s.geometry);
  for (auto& l : d.lights)
    std::visit(
        [&](auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, QuadLightDesc>) {
            pt(g.corner);
            vec(g.edge1);
            vec(g.edge2);
          } else if constexpr (std::is_same_v<T, PointLightDesc> ||
                               std::is_same_v<T, SpotLightDesc>) {
            pt(g.position);
            g.radius *= scale;
            g.intensity *= float(scale * scale);
          }  // sun and environment: at infinity, unchanged
        },
        l.light);
  const float per_unit = float(1.0 / scale);
  for (auto& m : d.media)
    std::visit(
        [&](auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, HomogeneousMediumDesc>) {
            g.sigma_a *= per_unit;
            g.sigma_s *= per_unit;
            if (g.bounds) {
              pt(g.bounds->min);
              pt(g.bounds->max);
            }
          } else {
            g.density_scale /= scale;
            g.transform =
                Transform::translate(offset) * Transform::scale(Vec3d(scale)) * g.transform;
          }
        },
        m.medium);
  return d;
}

}  // namespace vesper::test
