#include "renderer/scene/render_space.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vesper {
namespace {

// World-space bounds of everything with a position, to pick the unit scale.
struct Bounds {
  Vec3d lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
  void add(const Vec3d& p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  void add_parallelogram(const Vec3d& corner, const Vec3d& e1, const Vec3d& e2) {
    add(corner);
    add(corner + e1);
    add(corner + e2);
    add(corner + e1 + e2);
  }
  bool empty() const { return lo.x > hi.x; }
};

Bounds scene_bounds(const SceneDescription& d) {
  Bounds b;
  b.add(d.camera.from);
  for (const auto& s : d.shapes) {
    std::visit(
        [&](const auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, QuadShapeDesc>) {
            b.add_parallelogram(g.corner, g.edge1, g.edge2);
          } else if constexpr (std::is_same_v<T, SphereShapeDesc>) {
            b.add(g.center - Vec3d(g.radius));
            b.add(g.center + Vec3d(g.radius));
          } else {
            for (const auto& p : g.positions) b.add(p);
          }
        },
        s.geometry);
  }
  for (const auto& l : d.lights) {
    std::visit(
        [&](const auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, QuadLightDesc>) {
            b.add_parallelogram(g.corner, g.edge1, g.edge2);
          } else if constexpr (std::is_same_v<T, PointLightDesc> ||
                               std::is_same_v<T, SpotLightDesc>) {
            b.add(g.position);
          }
        },
        l.light);
  }
  for (const auto& m : d.media) {
    if (const auto* h = std::get_if<HomogeneousMediumDesc>(&m.medium)) {
      if (h->bounds) {
        b.add(h->bounds->min);
        b.add(h->bounds->max);
      }
    } else if (const auto* v = std::get_if<VdbMediumDesc>(&m.medium); v && v->density) {
      const IndexBox box = v->density->active_box();
      if (box.empty()) continue;
      for (int c = 0; c < 8; ++c) {
        const Vec3d ip{double((c & 1) ? box.max[0] + 1 : box.min[0] - 1),
                       double((c & 2) ? box.max[1] + 1 : box.min[1] - 1),
                       double((c & 4) ? box.max[2] + 1 : box.min[2] - 1)};
        b.add(v->transform.apply_point(v->density->index_to_world().apply_point(ip)));
      }
    }
  }
  return b;
}

}  // namespace

RenderSpace make_render_space(const SceneDescription& desc) {
  RenderSpace space;
  space.origin = desc.camera.from;
  const Bounds b = scene_bounds(desc);
  double radius = 0;
  for (int c = 0; c < 8; ++c) {
    const Vec3d corner{(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y,
                       (c & 4) ? b.hi.z : b.lo.z};
    radius = std::max(radius, length(corner - space.origin));
  }
  space.unit_scale = radius > 0 && std::isfinite(radius) ? radius : 1.0;
  space.inv_scale = 1.0 / space.unit_scale;
  space.radius = float(radius * space.inv_scale);
  if (!(space.radius > 0.f)) space.radius = 1.f;
  return space;
}

}  // namespace vesper
