#pragma once
// Render-time participating media (render space: coefficients are per
// render-space unit). A closed set: homogeneous boxes/fills and voxel grids.
// Media are volume objects: they fill their bounds whatever the surfaces do,
// and where they overlap their coefficients add.
#include <memory>
#include <variant>
#include <vector>

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

struct HomogeneousMedium {
  Rgb sigma_a, sigma_s;
  float g = 0;
  Box3 bounds;
  bool bounded = false;
};

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
};

using Medium = std::variant<HomogeneousMedium, GridMedium>;

}  // namespace vesper
