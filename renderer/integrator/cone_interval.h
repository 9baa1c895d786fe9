#pragma once
// The part of a ray segment inside a spot light's cone. Equiangular sampling
// aims only there: outside the cone the light adds nothing, and a shaft seen
// from the side (or a secondary ray in the fog beside it) would otherwise
// spend most of its distances near the apex, where the cone is thin.
//
// Any deterministic interval keeps the estimator unbiased: the MIS partner
// (distance sampling + next-event estimation) evaluates the same clipped
// density and takes full weight wherever it is zero.
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "renderer/math/vec.h"

namespace vesper {

struct TInterval {
  float t0 = 0, t1 = 0;
};

// The t in [ta, tb] with dot(x(t) - apex, axis) > cos_cone * |x(t) - apex|,
// x(t) = o + t d; nullopt when none. For cos_cone <= 0 (a cone wider than a
// hemisphere is not convex) the whole segment is returned.
inline std::optional<TInterval> cone_interval(const Vec3& o, const Vec3& d, const Vec3& apex,
                                              const Vec3& axis, float cos_cone, float ta,
                                              float tb) {
  if (!(tb > ta)) return std::nullopt;
  if (!(cos_cone > 0.f) || !std::isfinite(tb)) return TInterval{ta, tb};
  // The convex cone meets the line in one interval; its ends are roots of
  // (dot(v, axis))^2 = cos^2 |v|^2, v = x(t) - apex (the double cone's
  // quadric). Sort the roots inside (ta, tb) and keep the pieces whose
  // middle lies in the forward cone.
  const Vec3 v = o - apex;
  const double c2 = double(cos_cone) * cos_cone;
  const double va = dot(v, axis), da = dot(d, axis);
  const double a = da * da - c2 * dot(d, d);
  const double b = 2.0 * (va * da - c2 * dot(v, d));
  const double c = va * va - c2 * dot(v, v);
  std::array<double, 4> cuts{double(ta), double(tb), double(tb), double(tb)};
  int n = 1;
  auto add_root = [&](double t) {
    if (t > ta && t < tb) cuts[size_t(n++)] = t;
  };
  if (std::abs(a) > 1e-12) {
    const double disc = b * b - 4.0 * a * c;
    if (disc >= 0.0) {
      const double s = std::sqrt(disc);
      const double q = -0.5 * (b + (b >= 0.0 ? s : -s));  // no cancellation
      add_root(q / a);
      if (q != 0.0) add_root(c / q);
    }
  } else if (std::abs(b) > 0.0) {
    add_root(-c / b);
  }
  cuts[size_t(n++)] = tb;
  if (n == 4 && cuts[1] > cuts[2]) std::swap(cuts[1], cuts[2]);  // ta <= roots <= tb
  std::optional<TInterval> out;
  for (int i = 0; i + 1 < n; ++i) {
    const double mid = 0.5 * (cuts[size_t(i)] + cuts[size_t(i + 1)]);
    const Vec3 x = v + d * float(mid);
    if (!(dot(x, axis) > cos_cone * length(x))) continue;
    if (!out) out = TInterval{float(cuts[size_t(i)]), float(cuts[size_t(i + 1)])};
    out->t1 = float(cuts[size_t(i + 1)]);
  }
  return out;
}

}  // namespace vesper
