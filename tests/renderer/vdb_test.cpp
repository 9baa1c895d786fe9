// OpenVDB I/O, NanoVDB sampling, the majorant grid's DDA and the procedural
// cloud. Volumes are written from the tests into a temporary directory.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>

#include "renderer/volume/cloud.h"
#include "renderer/volume/majorant_grid.h"
#include "renderer/volume/vdb_io.h"
#include "vdb_fixtures.h"

namespace vesper {
namespace {

namespace fs = std::filesystem;
using test::dense_at;
using test::dense_trilinear;
using test::make_volume;
using test::VdbTempDir;
using test::write_volume;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const VdbError& e) {
    return e.what();
  }
  return "(no VdbError thrown)";
}

// A 6x5x4 block of distinct positive values.
DenseVolume small_block() {
  return make_volume(6, 5, 4,
                     [](int i, int j, int k) {
                       return 0.25f + 0.5f * float(i) + 0.125f * float(j) + 2.0f * float(k);
                     },
                     0.25, {1.0, -2.0, 3.0});
}

TEST(VdbIo, RoundTripKeepsValuesTransformAndBox) {
  VdbTempDir dir;
  const DenseVolume v = small_block();
  const fs::path file = write_volume(dir, "block.vdb", v);
  const auto grid = load_vdb_grid(file, "density");
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->name(), "density");
  for (int k = 0; k < v.nz; ++k)
    for (int j = 0; j < v.ny; ++j)
      for (int i = 0; i < v.nx; ++i)
        ASSERT_EQ(grid->voxel(i, j, k), dense_at(v, i, j, k)) << i << j << k;
  EXPECT_EQ(grid->voxel(-1, 0, 0), 0.0f);
  EXPECT_EQ(grid->voxel(6, 0, 0), 0.0f);
  const IndexBox box = grid->active_box();
  EXPECT_EQ(box.min, (std::array<int, 3>{0, 0, 0}));
  EXPECT_EQ(box.max, (std::array<int, 3>{5, 4, 3}));
  EXPECT_FLOAT_EQ(grid->max_value(), dense_at(v, 5, 4, 3));
  const Vec3d o = grid->index_to_world().apply_point({0, 0, 0});
  EXPECT_NEAR(o.x, 1.0, 1e-12);
  EXPECT_NEAR(o.y, -2.0, 1e-12);
  EXPECT_NEAR(o.z, 3.0, 1e-12);
  const Vec3d p = grid->index_to_world().apply_point({1, 2, 3});
  EXPECT_NEAR(p.x, 1.25, 1e-12);
  EXPECT_NEAR(p.y, -1.5, 1e-12);
  EXPECT_NEAR(p.z, 3.75, 1e-12);
  const Vec3d dv = grid->index_to_world().apply_vector({1, 0, 0});
  EXPECT_NEAR(dv.x, 0.25, 1e-12);
  EXPECT_NEAR(dv.y, 0.0, 1e-12);
  EXPECT_EQ(list_vdb_grids(file), std::vector<std::string>{"density: float"});
  // Written atomically: nothing but the file itself is left in the directory.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(VdbIo, DescribeReportsCountsBoxAndRange) {
  VdbTempDir dir;
  const fs::path file = write_volume(dir, "block.vdb", small_block());
  const auto infos = describe_vdb_grids(file);
  ASSERT_EQ(infos.size(), 1u);
  EXPECT_EQ(infos[0].name, "density");
  EXPECT_EQ(infos[0].value_type, "float");
  EXPECT_EQ(infos[0].grid_class, "fog volume");
  EXPECT_EQ(infos[0].active_voxels, 120u);
  EXPECT_TRUE(infos[0].has_range);
  EXPECT_FLOAT_EQ(float(infos[0].min_value), 0.25f);
  EXPECT_EQ(infos[0].active_box.max, (std::array<int, 3>{5, 4, 3}));
}

TEST(VdbSampling, TrilinearMatchesVoxelsHalfwaysAndAReference) {
  VdbTempDir dir;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> val(0.1f, 3.0f);
  const DenseVolume v = make_volume(9, 7, 8, [&](int, int, int) { return val(rng); });
  const auto grid = load_vdb_grid(write_volume(dir, "r.vdb", v), "density");
  // At voxel centres: exactly the voxel value.
  for (int k = 0; k < v.nz; ++k)
    for (int j = 0; j < v.ny; ++j)
      for (int i = 0; i < v.nx; ++i)
        ASSERT_EQ(grid->sample(Vec3(float(i), float(j), float(k))), dense_at(v, i, j, k));
  // Halfway between two neighbours: their average; at a cell centre: the mean of 8.
  for (int k = 0; k + 1 < v.nz; ++k)
    for (int j = 0; j + 1 < v.ny; ++j)
      for (int i = 0; i + 1 < v.nx; ++i) {
        const float a = dense_at(v, i, j, k);
        EXPECT_NEAR(grid->sample(Vec3(i + 0.5f, float(j), float(k))),
                    0.5f * (a + dense_at(v, i + 1, j, k)), 1e-6f);
        EXPECT_NEAR(grid->sample(Vec3(float(i), j + 0.5f, float(k))),
                    0.5f * (a + dense_at(v, i, j + 1, k)), 1e-6f);
        EXPECT_NEAR(grid->sample(Vec3(float(i), float(j), k + 0.5f)),
                    0.5f * (a + dense_at(v, i, j, k + 1)), 1e-6f);
        double mean8 = 0;
        for (int c = 0; c < 8; ++c)
          mean8 += dense_at(v, i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
        EXPECT_NEAR(grid->sample(Vec3(i + 0.5f, j + 0.5f, k + 0.5f)), mean8 / 8, 1e-5);
      }
  // Random points, including the fade-out band just outside the active box.
  std::uniform_real_distribution<float> ux(-1.5f, 9.5f), uy(-1.5f, 7.5f), uz(-1.5f, 8.5f);
  for (int n = 0; n < 5000; ++n) {
    const Vec3 p(ux(rng), uy(rng), uz(rng));
    ASSERT_NEAR(grid->sample(p), dense_trilinear(v, p.x, p.y, p.z), 2e-5)
        << p.x << " " << p.y << " " << p.z;
  }
  EXPECT_EQ(grid->sample(Vec3(-1.0f, 3.0f, 3.0f)), 0.0f);
  EXPECT_EQ(grid->sample(Vec3(1e20f, 0.0f, 0.0f)), 0.0f);
  EXPECT_EQ(grid->sample(Vec3(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f)), 0.0f);
}

TEST(VdbIo, MissingFileNamesTheFile) {
  VdbTempDir dir;
  const std::string msg = error_of([&] { load_vdb_grid(dir / "nope.vdb", "density"); });
  EXPECT_NE(msg.find("cannot open"), std::string::npos) << msg;
  EXPECT_NE(msg.find("nope.vdb"), std::string::npos) << msg;
  EXPECT_NE(error_of([&] { list_vdb_grids(dir / "nope.vdb"); }).find("nope.vdb"),
            std::string::npos);
}

TEST(VdbIo, NotAVdbFileIsAnOpenError) {
  VdbTempDir dir;
  const fs::path junk = dir / "junk.vdb";
  std::FILE* f = std::fopen(junk.c_str(), "wb");
  std::fputs("this is not a vdb file at all", f);
  std::fclose(f);
  const std::string msg = error_of([&] { load_vdb_grid(junk, "density"); });
  EXPECT_EQ(msg.rfind("cannot open " + junk.string() + ": ", 0), 0u) << msg;
}

TEST(VdbIo, MissingGridListsTheGridsTheFileHas) {
  VdbTempDir dir;
  const fs::path file = write_volume(dir, "block.vdb", small_block());
  const std::string msg = error_of([&] { load_vdb_grid(file, "densty"); });
  EXPECT_EQ(msg, file.string() + ": no grid named 'densty'; the file has: density (float)");
}

TEST(VdbIo, NanVoxelIsRejectedWithItsCoordinate) {
  // The writer keeps voxels with !(v < cutoff) active, and NaN < cutoff is
  // false, so a NaN in the dense block becomes an active NaN voxel on disk.
  VdbTempDir dir;
  DenseVolume v = small_block();
  v.values[(size_t(3) * v.ny + 1) * v.nx + 2] = std::numeric_limits<float>::quiet_NaN();
  const std::string msg =
      error_of([&] { load_vdb_grid(write_volume(dir, "nan.vdb", v), "density"); });
  EXPECT_NE(msg.find("voxel (2, 1, 3)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("nan"), std::string::npos) << msg;
  // Inf too (Inf >= cutoff, so it is active as well).
  v.values[(size_t(3) * v.ny + 1) * v.nx + 2] = std::numeric_limits<float>::infinity();
  const std::string msg2 =
      error_of([&] { load_vdb_grid(write_volume(dir, "inf.vdb", v), "density"); });
  EXPECT_NE(msg2.find("voxel (2, 1, 3)"), std::string::npos) << msg2;
  EXPECT_NE(msg2.find("inf"), std::string::npos) << msg2;
}

TEST(VdbIo, NegativeVoxelIsRejectedUnlessAllowed) {
  VdbTempDir dir;
  DenseVolume v = small_block();
  v.values[(size_t(0) * v.ny + 2) * v.nx + 1] = -0.5f;
  const fs::path file =
      write_volume(dir, "neg.vdb", v, "density", -1e30f);  // keeps negatives active
  const std::string msg = error_of([&] { load_vdb_grid(file, "density"); });
  EXPECT_NE(msg.find("voxel (1, 2, 0)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("-0.5"), std::string::npos) << msg;
  const auto grid = load_vdb_grid(file, "density", /*reject_negative=*/false);
  EXPECT_EQ(grid->voxel(1, 2, 0), -0.5f);
}

TEST(VdbIo, EmptyGridIsRejected) {
  VdbTempDir dir;
  const DenseVolume v = make_volume(4, 4, 4, [](int, int, int) { return 0.0f; });
  const std::string msg =
      error_of([&] { load_vdb_grid(write_volume(dir, "empty.vdb", v), "density"); });
  EXPECT_NE(msg.find("no active voxels"), std::string::npos) << msg;
}

TEST(VdbIo, WriterRejectsInconsistentVolumes) {
  VdbTempDir dir;
  DenseVolume v = small_block();
  v.values.pop_back();
  EXPECT_THROW(write_vdb_fog_volume(v, "density", dir / "bad.vdb"), VdbError);
  v = small_block();
  v.voxel_size = 0;
  EXPECT_THROW(write_vdb_fog_volume(v, "density", dir / "bad.vdb"), VdbError);
  EXPECT_FALSE(fs::exists(dir / "bad.vdb"));
}

// Files OpenVDB's own tool makes: a level set (non-zero background) and a
// vec3s grid. vdb_tool comes with libopenvdb-tools (scripts/setup).
TEST(VdbIo, NonFloatGridAndLevelSetAreRejected) {
  if (std::system("command -v vdb_tool >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "vdb_tool not installed";
  VdbTempDir dir;
  const fs::path file = dir / "tool.vdb";
  const std::string cmd = "vdb_tool -sphere dim=16 radius=1.0 name=ls -cpt keep=1 -write " +
                          file.string() + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string msg = error_of([&] { load_vdb_grid(file, "cpt_ls"); });
  EXPECT_NE(msg.find("value type vec3s"), std::string::npos) << msg;
  EXPECT_NE(msg.find("ls (float)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cpt_ls (vec3s)"), std::string::npos) << msg;
  const std::string msg2 = error_of([&] { load_vdb_grid(file, "ls"); });
  EXPECT_NE(msg2.find("background"), std::string::npos) << msg2;
  EXPECT_NE(msg2.find("level set"), std::string::npos) << msg2;
}

// ---------------------------------------------------------------- majorants

// Sparse blobs with empty space between them, offset from the origin.
std::shared_ptr<const DensityGrid> blob_grid(const VdbTempDir& dir, DenseVolume* out = nullptr) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const DenseVolume v = make_volume(40, 33, 27, [&](int i, int j, int k) {
    const float r = u(rng);
    const bool blob = (i - 8) * (i - 8) + (j - 10) * (j - 10) + (k - 9) * (k - 9) < 30 ||
                      (i - 30) * (i - 30) + (j - 25) * (j - 25) + (k - 18) * (k - 18) < 50;
    return blob ? 0.5f + 4.0f * r
                : (r < 0.002f ? 10.0f * r * 500.0f : 0.0f);  // rare spikes up to 10
  });
  if (out) *out = v;
  return load_vdb_grid(write_volume(dir, "blobs.vdb", v), "density");
}

// Independent clip of o + t d to the box [lo, hi] in double, within [tmin, tmax].
bool clip(const Vec3& o, const Vec3& d, double tmin, double tmax, const double lo[3],
          const double hi[3], double& t0, double& t1) {
  t0 = tmin;
  t1 = tmax;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 < t1;
}

struct Walked {
  std::vector<MajorantSegment> segs;
};
Walked walk_all(const MajorantGrid& mg, const Vec3& o, const Vec3& d, float tmin, float tmax) {
  Walked w;
  mg.walk(o, d, tmin, tmax, [&](const MajorantSegment& s) {
    w.segs.push_back(s);
    return true;
  });
  return w;
}

// The box walk() covers: the trilinear support, one voxel beyond the active
// box on each side. The cells (whole cells from lo) may reach past its upper
// side; walk() clips there (tests/stress/README.md, finding 1).
void grid_box(const DensityGrid& g, const MajorantGrid& mg, int cell, double lo[3], double hi[3]) {
  const IndexBox b = g.active_box();
  const int res[3] = {mg.cells_x(), mg.cells_y(), mg.cells_z()};
  for (int a = 0; a < 3; ++a) {
    lo[a] = b.min[a] - 1;
    hi[a] = std::min(lo[a] + double(res[a]) * cell, double(b.max[a] + 1));
  }
}

TEST(MajorantGrid, CellCountCoversTheActiveBoxPlusApron) {
  VdbTempDir dir;
  const auto g = blob_grid(dir);
  const MajorantGrid mg(*g, 8);
  const IndexBox b = g->active_box();
  EXPECT_EQ(mg.cells_x(), (b.max[0] - b.min[0] + 2 + 7) / 8);
  EXPECT_EQ(mg.cells_y(), (b.max[1] - b.min[1] + 2 + 7) / 8);
  EXPECT_EQ(mg.cells_z(), (b.max[2] - b.min[2] + 2 + 7) / 8);
}

TEST(MajorantGrid, RandomRaysSegmentsAreContiguousCoverTheClipAndBoundEverySample) {
  VdbTempDir dir;
  const auto g = blob_grid(dir);
  const int cell = 8;
  const MajorantGrid mg(*g, cell);
  double lo[3], hi[3];
  grid_box(*g, mg, cell, lo, hi);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  long samples = 0, nonzero_samples = 0, zero_segments = 0;
  int hits = 0;
  for (int r = 0; r < 3000; ++r) {
    // Origins inside and well outside the grid; some directions with zero components.
    Vec3 o(-20 + 80 * u(rng), -20 + 73 * u(rng), -20 + 67 * u(rng));
    Vec3 d(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
    if (r % 7 == 0) d.x = 0;
    if (r % 11 == 0) d.y = 0;
    if (r % 13 == 0) d.z = 0;
    if (d == Vec3(0.0f)) d.z = 1;
    d = d * (0.2f + 3.0f * u(rng));  // not unit length
    const float tmin = (r % 3 == 0) ? 0.0f : -5.0f * u(rng),
                tmax = (r % 5 == 0) ? 1e30f : 200.0f * u(rng);
    double c0, c1;
    const bool expect_hit = clip(o, d, tmin, tmax, lo, hi, c0, c1);
    const Walked w = walk_all(mg, o, d, tmin, tmax);
    if (!expect_hit || c1 - c0 < 1e-4) {
      // Grazing rays may or may not produce a sliver; anything emitted must be tiny.
      double len = 0;
      for (const auto& s : w.segs) len += s.t1 - s.t0;
      EXPECT_LT(len, 1e-3) << r;
      continue;
    }
    ++hits;
    ASSERT_FALSE(w.segs.empty()) << "ray " << r;
    const double tol = 1e-4 * std::max(1.0, std::abs(c1));
    EXPECT_NEAR(w.segs.front().t0, c0, tol) << r;
    EXPECT_NEAR(w.segs.back().t1, c1, tol) << r;
    for (size_t i = 0; i < w.segs.size(); ++i) {
      const auto& s = w.segs[i];
      ASSERT_LT(s.t0, s.t1) << r;
      if (i > 0) {
        ASSERT_EQ(w.segs[i - 1].t1, s.t0) << "gap or overlap, ray " << r;
        EXPECT_NE(w.segs[i - 1].max_density, s.max_density) << "equal runs are merged";
      }
      zero_segments += s.max_density == 0;
      // The bound: every trilinear sample in the segment is <= its majorant.
      for (int n = 0; n < 4; ++n) {
        const float t = s.t0 + (s.t1 - s.t0) * u(rng);
        const float v = g->sample(o + d * t);
        ++samples;
        nonzero_samples += v > 0;
        ASSERT_LE(v, s.max_density * (1 + 1e-6f)) << "ray " << r << " t " << t;
      }
    }
    // Outside the covered range the density is 0 (the grid box holds it all).
    for (float t :
         {float(c0) - 0.01f * float(c1 - c0) - 0.01f, float(c1) + 0.01f * float(c1 - c0) + 0.01f})
      if (t > tmin && t < tmax) {
        EXPECT_EQ(g->sample(o + d * t), 0.0f) << r;
      }
  }
  EXPECT_GT(hits, 600);
  EXPECT_GT(samples, 5000);
  EXPECT_GT(nonzero_samples, 500);
  EXPECT_GT(zero_segments, 100);  // empty cells are reported as gaps
  std::printf("majorant bound: %d rays hit, %ld samples (%ld non-zero)\n", hits, samples,
              nonzero_samples);
}

TEST(MajorantGrid, AxisAlignedRaysInsideAndOutside) {
  VdbTempDir dir;
  const auto g = blob_grid(dir);
  const int cell = 8;
  const MajorantGrid mg(*g, cell);
  double lo[3], hi[3];
  grid_box(*g, mg, cell, lo, hi);
  const Vec3 centre(20.3f, 16.1f, 13.7f);
  for (int a = 0; a < 3; ++a)
    for (float sign : {1.0f, -1.0f})
      for (bool inside : {true, false}) {
        Vec3 d(0.0f), o = centre;
        d[a] = sign * 2.0f;  // |d| = 2: t is half the index distance
        if (!inside) o[a] = float(sign > 0 ? lo[a] - 10 : hi[a] + 10);
        const Walked w = walk_all(mg, o, d, 0.0f, 1e9f);
        ASSERT_FALSE(w.segs.empty());
        const double enter = inside ? 0.0 : 5.0;
        const double exit = (sign > 0 ? (hi[a] - o[a]) : (o[a] - lo[a])) / 2.0;
        EXPECT_NEAR(w.segs.front().t0, enter, 1e-4) << a << sign << inside;
        EXPECT_NEAR(w.segs.back().t1, exit, 1e-4) << a << sign << inside;
        for (size_t i = 1; i < w.segs.size(); ++i) EXPECT_EQ(w.segs[i - 1].t1, w.segs[i].t0);
        for (const auto& s : w.segs)
          for (int n = 0; n <= 16; ++n) {
            const float t = s.t0 + (s.t1 - s.t0) * float(n) / 16;
            EXPECT_LE(g->sample(o + d * t), s.max_density * (1 + 1e-6f));
          }
      }
  // A ray along a cell boundary plane (x exactly on a boundary) still works.
  const Vec3 o(float(lo[0] + cell), 10.0f, -30.0f), d(0, 0, 1);
  const Walked w = walk_all(mg, o, d, 0.0f, 1e9f);
  ASSERT_FALSE(w.segs.empty());
  EXPECT_NEAR(w.segs.front().t0, lo[2] + 30, 1e-4);
  EXPECT_NEAR(w.segs.back().t1, hi[2] + 30, 1e-4);
  // Parallel to an axis but outside the slab: nothing.
  EXPECT_TRUE(walk_all(mg, Vec3(-50, 10, -30), Vec3(0, 0, 1), 0, 1e9f).segs.empty());
}

TEST(MajorantGrid, VisitorCanStopTheWalk) {
  VdbTempDir dir;
  const auto g = blob_grid(dir);
  const MajorantGrid mg(*g, 4);
  int calls = 0;
  mg.walk(Vec3(-5, 10, 9), Vec3(1, 0, 0), 0, 1e9f,
          [&](const MajorantSegment&) { return ++calls < 2; });
  EXPECT_EQ(calls, 2);
}

TEST(MajorantGrid, GlobalIsOneSegmentWithTheGridMax) {
  VdbTempDir dir;
  const auto g = blob_grid(dir);
  const MajorantGrid mg = MajorantGrid::global(*g);
  EXPECT_EQ(mg.cells_x() * mg.cells_y() * mg.cells_z(), 1);
  const Walked w = walk_all(mg, Vec3(-10, 3, 4), Vec3(1, 0.1f, 0.05f), 0, 1e9f);
  ASSERT_EQ(w.segs.size(), 1u);
  EXPECT_EQ(w.segs[0].max_density, g->max_value());
  const IndexBox b = g->active_box();
  EXPECT_NEAR(w.segs[0].t0, b.min[0] - 1 + 10, 1e-4);
  EXPECT_NEAR(w.segs[0].t1, b.max[0] + 1 + 10, 1e-3);
}

TEST(MajorantGrid, FinerCellsAreTighterAndEmptyCellsAreZero) {
  VdbTempDir dir;
  const auto g = blob_grid(dir);
  const MajorantGrid fine(*g, 4);
  // A ray through the empty region between the blobs has zero majorant somewhere.
  double zero_len = 0;
  fine.walk(Vec3(0, 18, 0), Vec3(1, 0, 1), 0, 1e9f, [&](const MajorantSegment& s) {
    if (s.max_density == 0) zero_len += s.t1 - s.t0;
    return true;
  });
  EXPECT_GT(zero_len, 0.0);
}

// ---------------------------------------------------------- real smoke.vdb

TEST(SmokeVdb, LoadsTheRealSmokeSimulation) {
  const fs::path file = fs::path(VESPER_SOURCE_DIR) / "../shared/data/smoke.vdb";
  if (!fs::exists(file))
    GTEST_SKIP() << "real test data absent: " << file << " (shared data is not in the repo)";
  const auto names = list_vdb_grids(file);
  ASSERT_FALSE(names.empty());
  std::printf("smoke.vdb grids:");
  for (const auto& n : names) std::printf(" [%s]", n.c_str());
  std::printf("\n");
  EXPECT_NE(std::find(names.begin(), names.end(), "density: float"), names.end());

  auto t0 = std::chrono::steady_clock::now();
  const auto grid = load_vdb_grid(file, "density");
  const double load_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const IndexBox b = grid->active_box();
  ASSERT_FALSE(b.empty());
  std::printf("smoke density: box [%d %d %d]..[%d %d %d], max %.4g, loaded in %.3f s\n", b.min[0],
              b.min[1], b.min[2], b.max[0], b.max[1], b.max[2], grid->max_value(), load_s);
  EXPECT_GT(grid->max_value(), 0.0f);
  const Vec3d w0 = grid->index_to_world().apply_point({0, 0, 0});
  EXPECT_TRUE(std::isfinite(w0.x) && std::isfinite(w0.y) && std::isfinite(w0.z));

  // Every voxel in the box is finite, >= 0 and <= max_value.
  long positive = 0;
  for (int k = b.min[2]; k <= b.max[2]; ++k)
    for (int j = b.min[1]; j <= b.max[1]; ++j)
      for (int i = b.min[0]; i <= b.max[0]; ++i) {
        const float v = grid->voxel(i, j, k);
        ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= grid->max_value())
            << i << " " << j << " " << k;
        positive += v > 0;
      }
  EXPECT_GT(positive, 100000);

  // A million random trilinear samples in the active box.
  std::mt19937 rng(1);
  std::vector<Vec3> pts(1000000);
  for (auto& p : pts)
    for (int a = 0; a < 3; ++a)
      p[a] = std::uniform_real_distribution<float>(float(b.min[a]), float(b.max[a]))(rng);
  t0 = std::chrono::steady_clock::now();
  double sum = 0;
  for (const Vec3& p : pts) sum += grid->sample(p);
  const double sample_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("smoke: 1e6 random trilinear samples in %.3f s (%.1f ns/sample, mean %.4g)\n",
              sample_s, sample_s * 1e3, sum / 1e6);
  EXPECT_TRUE(std::isfinite(sum));

  // Coherent samples (a ray march), which is how the tracker uses them.
  t0 = std::chrono::steady_clock::now();
  sum = 0;
  for (int n = 0; n < 1000000; ++n) {
    const float t = float(n % 1000) / 1000.0f;
    const int r = n / 1000;
    sum += grid->sample(
        Vec3(b.min[0] + t * (b.max[0] - b.min[0]), b.min[1] + (r % 200) * 1.1f, 56.0f + r * 0.01f));
  }
  const double march_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("smoke: 1e6 coherent (ray-march) samples in %.3f s (%.1f ns/sample)\n", march_s,
              march_s * 1e3);

  t0 = std::chrono::steady_clock::now();
  const MajorantGrid mg(*grid, 16);
  const double mg_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("smoke: majorant grid %dx%dx%d cells built in %.3f s\n", mg.cells_x(), mg.cells_y(),
              mg.cells_z(), mg_s);
}

// ------------------------------------------------------------------- cloud

TEST(Cloud, DensityInUnitRangeNonEmptyInsideTheVolumeAndDeterministic) {
  CloudParams p;
  p.resolution = 48;
  p.seed = 3;
  const DenseVolume a = generate_cloud(p);
  EXPECT_EQ(a.nx, 48);
  EXPECT_EQ(a.ny, 24);
  EXPECT_EQ(a.nz, 48);
  ASSERT_EQ(a.values.size(), size_t(48) * 24 * 48);
  long inside = 0, some = 0;
  for (float v : a.values) {
    ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << v;
    inside += v == 1.0f;
    some += v > 0.0f;
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(some, inside);  // a soft band, not a hard edge
  EXPECT_LT(some, long(a.values.size()) / 2);
  // The cloud does not touch the sides or top of the volume (nothing is cut off).
  for (int k = 0; k < a.nz; ++k)
    for (int j = 0; j < a.ny; ++j)
      for (int i = 0; i < a.nx; ++i)
        if (i == 0 || i == a.nx - 1 || k == 0 || k == a.nz - 1 || j == 0 || j == a.ny - 1) {
          ASSERT_EQ(dense_at(a, i, j, k), 0.0f) << i << " " << j << " " << k;
        }
  // Flat bottom: the lowest occupied layer is much wider than the highest.
  auto layer_count = [&](int j) {
    long n = 0;
    for (int k = 0; k < a.nz; ++k)
      for (int i = 0; i < a.nx; ++i) n += dense_at(a, i, j, k) > 0.5f;
    return n;
  };
  int lowest = -1, highest = -1;
  for (int j = 0; j < a.ny; ++j)
    if (layer_count(j) > 0) {
      if (lowest < 0) lowest = j;
      highest = j;
    }
  ASSERT_GE(lowest, 0);
  EXPECT_GT(layer_count(lowest), 4 * layer_count(highest));

  EXPECT_EQ(generate_cloud(p).values, a.values);  // deterministic
  p.seed = 4;
  EXPECT_NE(generate_cloud(p).values, a.values);  // the seed matters
  p.resolution = 2;
  EXPECT_THROW(generate_cloud(p), std::invalid_argument);
}

TEST(Cloud, WritesAFogVolumeThatLoads) {
  VdbTempDir dir;
  CloudParams p;
  p.resolution = 32;
  const DenseVolume v = generate_cloud(p);
  const auto g = load_vdb_grid(write_volume(dir, "cloud.vdb", v), "density");
  EXPECT_FALSE(g->active_box().empty());
  EXPECT_LE(g->max_value(), 1.0f);
  EXPECT_GT(g->max_value(), 0.99f);
  const Vec3d c = g->index_to_world().apply_point({15.5, 0, 15.5});
  EXPECT_NEAR(c.x, 0.0, 1e-9);  // centred on x = z = 0, base at y = 0
  EXPECT_NEAR(c.y, 0.0, 1e-9);
  EXPECT_NEAR(c.z, 0.0, 1e-9);
}

TEST(Cloud, NoiseAndSmoothMin) {
  EXPECT_FLOAT_EQ(smooth_min(1.0f, 3.0f, 0.5f), 1.0f);
  EXPECT_LT(smooth_min(1.0f, 1.1f, 0.5f), 1.0f);
  EXPECT_EQ(gradient_noise(3, -2, 5, 9), 0.0f);  // zero at lattice points
  float lo = 0, hi = 0;
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-50, 50);
  for (int n = 0; n < 20000; ++n) {
    const float v = fbm(u(rng), u(rng), u(rng), 5, 7);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_LT(lo, -0.3f);
  EXPECT_GT(hi, 0.3f);
  EXPECT_GT(lo, -1.1f);
  EXPECT_LT(hi, 1.1f);
}

}  // namespace
}  // namespace vesper
