// Coarse grid of maximum densities + Amanatides-Woo 3D DDA.
//
// Index-space layout. A trilinear sample at p reads voxels floor(p) and
// floor(p)+1 on each axis, so it can be non-zero only in the open box
// (active.min - 1, active.max + 1). The majorant grid covers that box with
// cubic cells, [lo, lo + res*C] with lo = active.min - 1 and C = cell_voxels;
// the last cells reach past active.max + 1, so walk() clips rays to the box
// itself. (Without the clip, a ray through the overhang got the cell's
// majorant over empty space: null collisions at a rate of density_scale per
// unit, minutes per tiny image at a density_scale of 1e5; tests/stress.)
// A cell spanning [a, a+C] on an axis can read voxels a .. a+C (with floor); its max is taken over
// voxels a-1 .. a+C+1, one voxel of apron on each side, so the bound also holds for points the
// DDA's floating-point boundaries put a hair into the neighbouring cell.
//
// walk() emits segments for every cell it crosses, including cells with max 0
// (the caller sees the gaps as max_density == 0 and skips them), but merges
// runs of consecutive cells with the same max into one segment, so long empty
// stretches cost one callback. Segments are contiguous, front to back, and
// together cover exactly [tmin, tmax] clipped to the support box.
#include "renderer/volume/majorant_grid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vesper {

MajorantGrid::MajorantGrid(const DensityGrid& grid, int cell_voxels) {
  const IndexBox box = grid.active_box();
  if (box.empty()) return;
  const int C = std::max(1, cell_voxels);
  std::array<int, 3> lo{};
  for (int a = 0; a < 3; ++a) {
    lo[a] = box.min[a] - 1;
    const long long extent = (long long)box.max[a] + 1 - lo[a];  // >= 2
    res_[a] = int((extent + C - 1) / C);
  }
  lo_ = Vec3(float(lo[0]), float(lo[1]), float(lo[2]));
  hi_ = Vec3(float(box.max[0] + 1), float(box.max[1] + 1), float(box.max[2] + 1));
  cell_size_ = Vec3(float(C));
  max_.assign(size_t(res_[0]) * res_[1] * res_[2], 0.0f);

  // One task per z-layer of cells; each cell scans its voxels plus the apron,
  // clamped to the active box (everything outside it is background 0).
  tbb::parallel_for(0, res_[2], [&](int cz) {
    for (int cy = 0; cy < res_[1]; ++cy)
      for (int cx = 0; cx < res_[0]; ++cx) {
        const int c[3] = {cx, cy, cz};
        int v0[3], v1[3];
        bool empty = false;
        for (int a = 0; a < 3; ++a) {
          v0[a] = std::max(box.min[a], lo[a] + c[a] * C - 1);
          v1[a] = std::min(box.max[a], lo[a] + (c[a] + 1) * C + 1);
          empty |= v1[a] < v0[a];
        }
        float m = 0.0f;
        if (!empty)
          for (int k = v0[2]; k <= v1[2]; ++k)
            for (int j = v0[1]; j <= v1[1]; ++j)
              for (int i = v0[0]; i <= v1[0]; ++i) m = std::max(m, grid.voxel(i, j, k));
        max_[(size_t(cz) * res_[1] + cy) * res_[0] + cx] = m;
      }
  });
}

MajorantGrid MajorantGrid::global(const DensityGrid& grid) {
  MajorantGrid g;
  const IndexBox box = grid.active_box();
  if (box.empty()) return g;
  g.res_ = {1, 1, 1};
  g.lo_ = Vec3(float(box.min[0] - 1), float(box.min[1] - 1), float(box.min[2] - 1));
  g.cell_size_ = Vec3(float(box.max[0] - box.min[0] + 2), float(box.max[1] - box.min[1] + 2),
                      float(box.max[2] - box.min[2] + 2));
  g.hi_ = g.lo_ + g.cell_size_;
  g.max_ = {std::max(0.0f, grid.max_value())};
  return g;
}

void MajorantGrid::walk(const Vec3& o, const Vec3& d, float tmin, float tmax,
                        const std::function<bool(const MajorantSegment&)>& visit) const {
  if (max_.empty() || !(tmin < tmax)) return;
  // 1. Clip the ray to the trilinear support box (slab test; zero direction
  //    components handled explicitly, so no 0 * inf).
  float t0 = tmin, t1 = tmax;
  for (int a = 0; a < 3; ++a) {
    const float lo = lo_[a], hi = hi_[a];
    if (d[a] == 0.0f) {
      if (!(o[a] >= lo && o[a] <= hi)) return;
      continue;
    }
    const float inv = 1.0f / d[a];
    float ta = (lo - o[a]) * inv, tb = (hi - o[a]) * inv;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 < t1)) return;  // also catches NaN from a degenerate ray

  // 2. Starting cell and per-axis crossing parameters. Boundary crossings are
  //    computed directly as (plane - o) / d, not by accumulating a delta, so
  //    there is no drift over long walks.
  int cell[3], step[3];
  float t_next[3];
  const float inf = std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a) {
    const float p = o[a] + t0 * d[a];
    int c = int(std::floor((p - lo_[a]) / cell_size_[a]));
    c = std::clamp(c, 0, res_[a] - 1);
    cell[a] = c;
    if (d[a] > 0.0f) {
      step[a] = 1;
      t_next[a] = (lo_[a] + float(c + 1) * cell_size_[a] - o[a]) / d[a];
    } else if (d[a] < 0.0f) {
      step[a] = -1;
      t_next[a] = (lo_[a] + float(c) * cell_size_[a] - o[a]) / d[a];
    } else {
      step[a] = 0;
      t_next[a] = inf;
    }
  }

  // 3. March, merging runs of equal max into one segment.
  MajorantSegment pending{t0, t0, -1.0f};
  float t = t0, m = 0.0f;
  for (;;) {
    m = max_[(size_t(cell[2]) * res_[1] + cell[1]) * res_[0] + cell[0]];
    const int axis =
        t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2) : (t_next[1] < t_next[2] ? 1 : 2);
    const float t_exit = std::min(std::max(t_next[axis], t), t1);
    if (t_exit > t) {
      if (m == pending.max_density) {
        pending.t1 = t_exit;
      } else {
        if (pending.t1 > pending.t0 && !visit(pending)) return;
        pending = {t, t_exit, m};
      }
      t = t_exit;
    }
    if (t >= t1) break;
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= res_[axis]) break;
    t_next[axis] =
        (lo_[axis] + float(cell[axis] + (step[axis] > 0 ? 1 : 0)) * cell_size_[axis] - o[axis]) /
        d[axis];
  }
  // Close the walk at t1 exactly (the last cell boundary may differ from the
  // clipped t1 by rounding).
  pending.t1 = std::max(pending.t1, t1);
  if (pending.max_density < 0.0f) pending.max_density = m;  // only degenerate steps were taken
  if (pending.t1 > pending.t0) visit(pending);
}

}  // namespace vesper
