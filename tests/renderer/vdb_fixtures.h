#pragma once
// Helpers for the OpenVDB tests: a per-test temporary directory
// (tests/common/temp_dir.h) and small dense volumes written through
// write_vdb_fog_volume (no committed binaries).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>

#include "renderer/volume/vdb_io.h"
#include "tests/common/temp_dir.h"

namespace vesper::test {

using VdbTempDir = TempDir;

// nx*ny*nz voxels with value f(i, j, k).
inline DenseVolume make_volume(int nx, int ny, int nz, const std::function<float(int, int, int)>& f,
                               double voxel_size = 1.0, Vec3d origin = {}) {
  DenseVolume v;
  v.nx = nx;
  v.ny = ny;
  v.nz = nz;
  v.voxel_size = voxel_size;
  v.origin = origin;
  v.values.resize(size_t(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) v.values[(size_t(k) * ny + j) * nx + i] = f(i, j, k);
  return v;
}

inline float dense_at(const DenseVolume& v, int i, int j, int k) {
  if (i < 0 || j < 0 || k < 0 || i >= v.nx || j >= v.ny || k >= v.nz) return 0.0f;
  return v.values[(size_t(k) * v.ny + j) * v.nx + i];
}

// Reference trilinear interpolation of a dense volume (0 outside), in double.
inline double dense_trilinear(const DenseVolume& v, double x, double y, double z) {
  const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const int i = int(fx), j = int(fy), k = int(fz);
  const double u = x - fx, w1 = y - fy, w2 = z - fz;
  double r = 0;
  for (int c = 0; c < 8; ++c) {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    const double wt = (di ? u : 1 - u) * (dj ? w1 : 1 - w1) * (dk ? w2 : 1 - w2);
    r += wt * dense_at(v, i + di, j + dj, k + dk);
  }
  return r;
}

// Writes v as fog-volume grid `grid` into dir/file and returns the path.
inline std::filesystem::path write_volume(const VdbTempDir& dir, const std::string& file,
                                          const DenseVolume& v, const std::string& grid = "density",
                                          float cutoff = 1e-6f) {
  const std::filesystem::path p = dir / file;
  write_vdb_fog_volume(v, grid, p, cutoff);
  return p;
}

}  // namespace vesper::test
