#include "renderer/integrator/photon_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vesper {

PhotonMap::PhotonMap(std::vector<Photon> photons, float radius) : radius_(radius) {
  if (!(radius > 0.f)) throw std::invalid_argument("photon map: the radius must be > 0");
  if (photons.size() >= UINT32_MAX) throw std::invalid_argument("photon map: too many photons");
  if (photons.empty()) return;
  Vec3 lo = photons[0].p, hi = photons[0].p;
  for (const Photon& ph : photons) {
    lo = min(lo, ph.p);
    hi = max(hi, ph.p);
  }
  // Cells no smaller than the radius (a query reads 3^3 cells), and no
  // more of them than about two per photon (memory).
  const Vec3 extent = hi - lo;
  float cell = radius;
  const double most_cells = 2.0 * double(photons.size()) + 64.0;
  for (;;) {
    double cells = 1;
    for (int a = 0; a < 3; ++a) cells *= std::floor(double(extent[a]) / cell) + 1;
    if (cells <= most_cells) break;
    cell *= 1.25f;
  }
  lo_ = lo;
  inv_cell_ = 1.f / cell;
  for (int a = 0; a < 3; ++a) dims_[a] = int(std::floor(extent[a] * inv_cell_)) + 1;
  const size_t cells = size_t(dims_[0]) * size_t(dims_[1]) * size_t(dims_[2]);

  // Counting sort by cell, stable: the order follows the input's.
  std::vector<uint32_t> cell_of(photons.size());
  starts_.assign(cells + 1, 0);
  for (size_t i = 0; i < photons.size(); ++i) {
    const Vec3& p = photons[i].p;
    cell_of[i] = uint32_t(cell_index(cell_coord(p, 0), cell_coord(p, 1), cell_coord(p, 2)));
    ++starts_[cell_of[i] + 1];
  }
  for (size_t c = 0; c < cells; ++c) starts_[c + 1] += starts_[c];
  std::vector<uint32_t> next(starts_.begin(), starts_.end() - 1);
  photons_.resize(photons.size());
  for (size_t i = 0; i < photons.size(); ++i) photons_[next[cell_of[i]]++] = photons[i];
}

int PhotonMap::cell_coord(const Vec3& p, int axis) const {
  const float f = (p[axis] - lo_[axis]) * inv_cell_;
  // Points outside the bounds read the border cells (their photons are
  // still checked by distance); NaN reads cell 0.
  if (!(f > 0.f)) return 0;
  return std::min(int(f), dims_[axis] - 1);
}

}  // namespace vesper
