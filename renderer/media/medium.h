#pragma once
// Render-time participating media (render space: coefficients are per
// render-space unit). A closed set: homogeneous boxes/fills and voxel grids.
// Media are volume objects: they fill their bounds whatever the surfaces do,
// and where they overlap their coefficients add.
#include <memory>
#include <variant>
#include <vector>

#include "renderer/core/motion_steps.h"
#include "renderer/core/ray.h"
#include "renderer/math/rgb.h"
#include "renderer/math/transform.h"
#include "renderer/volume/density_grid.h"
#include "renderer/volume/majorant_grid.h"

namespace vesper {

// Axis-aligned box; an unbounded medium has lo = -inf, hi = +inf.
struct Box3 {
  Vec3 lo, hi;
  // Parametric overlap of o + t d with the box, clipped to [0, tmax]; false if none.
  bool clip(const Vec3& o, const Vec3& d, float tmax, float* t0, float* t1) const;
};

// Motion blur: a moving medium holds its box (or render -> index map) at
// each step of the shutter (core/motion_steps.h); at a ray's time the box's
// corners, or the index positions of a point, are interpolated linearly
// between steps. Empty steps: still.

struct HomogeneousMedium {
  Rgb sigma_a, sigma_s;
  float g = 0;
  Box3 bounds;
  bool bounded = false;
  std::vector<Box3> bounds_steps = {};  // motion blur (bounded only); empty = bounds

  Box3 box_at(float time) const {
    if (bounds_steps.empty()) return bounds;
    const auto [k, f] = step_position(bounds_steps.size(), time);
    return {lerp_steps(bounds_steps[k].lo, bounds_steps[k + 1].lo, f),
            lerp_steps(bounds_steps[k].hi, bounds_steps[k + 1].hi, f)};
  }
  bool contains(const Vec3& p, float time) const {
    if (!bounded) return true;
    const Box3 b = box_at(time);
    return p.x >= b.lo.x && p.y >= b.lo.y && p.z >= b.lo.z && p.x <= b.hi.x && p.y <= b.hi.y &&
           p.z <= b.hi.z;
  }
};

// `still` applied to v (a point or a vector), or at `time` between `steps`.
inline Vec3 map_at(const std::vector<Transformf>& steps, const Transformf& still, float time,
                   const Vec3& v, bool point) {
  auto apply = [&](const Transformf& t) { return point ? t.apply_point(v) : t.apply_vector(v); };
  if (steps.empty()) return apply(still);
  const auto [k, f] = step_position(steps.size(), time);
  return lerp_steps(apply(steps[k]), apply(steps[k + 1]), f);
}

struct GridMedium {
  std::shared_ptr<const DensityGrid> density;
  std::shared_ptr<const DensityGrid> emission;  // may be null
  std::shared_ptr<const MajorantGrid> majorants;
  std::shared_ptr<const MajorantGrid> emission_majorants;  // when emission is set
  Transformf render_to_index;
  Transformf render_to_emission_index;  // when emission is set
  float density_scale = 1;              // times sigma_a / sigma_s below
  Rgb sigma_a, sigma_s;                 // per render unit at density 1
  float g = 0;
  Rgb emission_coefficient;  // per render unit at emission value 1
  // Motion blur: render_to_index (and the emission's) at each step; empty = still.
  std::vector<Transformf> index_steps = {}, emission_index_steps = {};

  Vec3 index_point(const Vec3& p, float time) const {
    return map_at(index_steps, render_to_index, time, p, true);
  }
  Vec3 index_vector(const Vec3& v, float time) const {
    return map_at(index_steps, render_to_index, time, v, false);
  }
};

using Medium = std::variant<HomogeneousMedium, GridMedium>;

}  // namespace vesper
