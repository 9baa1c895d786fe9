#pragma once
// Composition and inversion of 3x4 affine maps (double), for chaining
// render space -> world -> grid index space.
#include <cmath>
#include <optional>

#include "renderer/volume/density_grid.h"

namespace vesper {

// (a ∘ b)(p) = a(b(p))
inline Affine3d compose(const Affine3d& a, const Affine3d& b) {
  Affine3d r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      double v = j == 3 ? a.m[size_t(i * 4 + 3)] : 0.0;
      for (int k = 0; k < 3; ++k) v += a.m[size_t(i * 4 + k)] * b.m[size_t(k * 4 + j)];
      r.m[size_t(i * 4 + j)] = v;
    }
  }
  return r;
}

inline std::optional<Affine3d> inverse(const Affine3d& a) {
  const auto& m = a.m;
  const double c00 = m[5] * m[10] - m[6] * m[9], c01 = m[6] * m[8] - m[4] * m[10],
               c02 = m[4] * m[9] - m[5] * m[8];
  const double det = m[0] * c00 + m[1] * c01 + m[2] * c02;
  if (!(std::abs(det) > 1e-300) || !std::isfinite(det)) return std::nullopt;
  const double id = 1.0 / det;
  Affine3d r;
  r.m = {c00 * id, (m[2] * m[9] - m[1] * m[10]) * id, (m[1] * m[6] - m[2] * m[5]) * id, 0,
         c01 * id, (m[0] * m[10] - m[2] * m[8]) * id, (m[2] * m[4] - m[0] * m[6]) * id, 0,
         c02 * id, (m[1] * m[8] - m[0] * m[9]) * id,  (m[0] * m[5] - m[1] * m[4]) * id, 0};
  const Vec3d t{m[3], m[7], m[11]};
  for (int i = 0; i < 3; ++i) {
    r.m[size_t(i * 4 + 3)] =
        -(r.m[size_t(i * 4)] * t.x + r.m[size_t(i * 4 + 1)] * t.y + r.m[size_t(i * 4 + 2)] * t.z);
  }
  return r;
}

inline Affine3d affine_from_transform_rows(const double* rows12) {
  Affine3d r;
  for (int i = 0; i < 12; ++i) r.m[size_t(i)] = rows12[i];
  return r;
}

}  // namespace vesper
