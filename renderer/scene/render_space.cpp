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

// What each description adds to the bounds: its extent; lights at infinity
// and unbounded media add nothing.
void include(Bounds& b, const QuadShapeDesc& q) { b.add_parallelogram(q.corner, q.edge1, q.edge2); }
void include(Bounds& b, const SphereShapeDesc& s) {
  b.add(s.center - Vec3d(s.radius));
  b.add(s.center + Vec3d(s.radius));
}
void include(Bounds& b, const MeshShapeDesc& m) {
  for (const auto& p : m.positions) b.add(p);
}
void include(Bounds& b, const QuadLightDesc& q) { b.add_parallelogram(q.corner, q.edge1, q.edge2); }
void include(Bounds& b, const PointLightDesc& p) { b.add(p.position); }
void include(Bounds& b, const SpotLightDesc& s) { b.add(s.position); }
void include(Bounds&, const SunLightDesc&) {}
void include(Bounds&, const EnvironmentLightDesc&) {}
void include(Bounds& b, const HomogeneousMediumDesc& h) {
  if (!h.bounds) return;
  b.add(h.bounds->min);
  b.add(h.bounds->max);
}
void include(Bounds& b, const VdbMediumDesc& v) {
  if (!v.density) return;
  const IndexBox box = v.density->active_box();
  if (box.empty()) return;
  for (int c = 0; c < 8; ++c) {
    const Vec3d ip{double((c & 1) ? box.max[0] + 1 : box.min[0] - 1),
                   double((c & 2) ? box.max[1] + 1 : box.min[1] - 1),
                   double((c & 4) ? box.max[2] + 1 : box.min[2] - 1)};
    b.add(v.transform.apply_point(v.density->index_to_world().apply_point(ip)));
  }
}

// A moving medium's extent at each step.
void include_steps(Bounds& b, const MediumDesc& m) {
  if (const auto* h = std::get_if<HomogeneousMediumDesc>(&m.medium)) {
    for (const BoxDesc& box : h->bounds_steps) {
      b.add(box.min);
      b.add(box.max);
    }
    return;
  }
  VdbMediumDesc at_step = std::get<VdbMediumDesc>(m.medium);
  for (const Transform& t : std::get<VdbMediumDesc>(m.medium).transform_steps) {
    at_step.transform = t;
    include(b, at_step);
  }
}

Bounds scene_bounds(const SceneDescription& d) {
  Bounds b;
  b.add(d.camera.from);
  for (const auto& c : d.camera_steps) b.add(c.from);  // motion blur
  const auto add = [&](const auto& desc) { include(b, desc); };
  for (const auto& s : d.shapes) {
    std::visit(add, s.geometry);
    for (const auto& step : s.steps) std::visit(add, step);
  }
  for (const auto& l : d.lights) std::visit(add, l.light);
  for (const auto& m : d.media) {
    std::visit(add, m.medium);
    include_steps(b, m);  // motion blur
  }
  return b;
}

template <typename Variant>
double extent_of_variant(const Variant& v) {
  Bounds b;
  std::visit([&](const auto& desc) { include(b, desc); }, v);
  if (b.empty()) return 0;
  double e = 0;
  for (int i = 0; i < 3; ++i)
    for (const double c : {b.lo[i], b.hi[i]})
      e = std::isnan(c) ? INFINITY : std::max(e, std::abs(c));
  return e;
}

}  // namespace

double extent_of(const ShapeDesc& shape) { return extent_of_variant(shape.geometry); }
double extent_of(const LightDesc& light) { return extent_of_variant(light.light); }
double extent_of(const MediumDesc& medium) { return extent_of_variant(medium.medium); }

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
