#pragma once
// Photons for photon merging (photon_merging.h): light-subpath vertices in
// media, found by distance. A uniform grid over the photons' bounds, cells
// at least the query radius wide, photons sorted by cell (counting sort), so
// a query reads the 27 cells around it. Hand-written: no Debian package
// offers a fixed-radius point grid (nanoflann's kd-tree answers k-nearest
// and radius queries, but at several times the cost per query here, where
// every query has the same radius).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "renderer/math/rgb.h"
#include "renderer/math/vec.h"

namespace vesper {

struct Photon {
  Vec3 p;
  Vec3 dir;  // the direction the light travelled to p
  // The light subpath's weight arriving at p (flux times scattering weights);
  // in a medium, over sigma_s at p.
  Rgb weight;
  uint32_t light = 0;
  Vec3 n{};  // a surface photon's geometric normal; zero in a medium
};

class PhotonMap {
 public:
  PhotonMap() = default;
  // Takes the photons; queries find those within `radius` of a point.
  PhotonMap(std::vector<Photon> photons, float radius);

  float radius() const { return radius_; }
  size_t size() const { return photons_.size(); }

  // Calls f(photon) for each photon within radius() of x (any order; the
  // same order for the same map and x).
  template <typename F>
  void for_each_near(const Vec3& x, F&& f) const {
    if (photons_.empty()) return;
    const float r2 = radius_ * radius_;
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = cell_coord(x, a);
    for (int z = std::max(c[2] - 1, 0); z <= std::min(c[2] + 1, dims_[2] - 1); ++z)
      for (int y = std::max(c[1] - 1, 0); y <= std::min(c[1] + 1, dims_[1] - 1); ++y)
        for (int xx = std::max(c[0] - 1, 0); xx <= std::min(c[0] + 1, dims_[0] - 1); ++xx) {
          const size_t cell = cell_index(xx, y, z);
          for (uint32_t i = starts_[cell]; i < starts_[cell + 1]; ++i)
            if (length_squared(photons_[i].p - x) <= r2) f(photons_[i]);
        }
  }

 private:
  int cell_coord(const Vec3& p, int axis) const;
  size_t cell_index(int x, int y, int z) const {
    return (size_t(z) * size_t(dims_[1]) + size_t(y)) * size_t(dims_[0]) + size_t(x);
  }

  std::vector<Photon> photons_;   // sorted by cell
  std::vector<uint32_t> starts_;  // cell -> its first photon; one more entry at the end
  Vec3 lo_;
  float inv_cell_ = 0, radius_ = 0;
  int dims_[3] = {0, 0, 0};
};

}  // namespace vesper
