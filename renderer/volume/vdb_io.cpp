// The only translation unit that includes OpenVDB (its headers cost seconds of
// compile). Loads float grids, validates them, converts them to NanoVDB.
#include "renderer/volume/vdb_io.h"

#include <openvdb/openvdb.h>
#include <unistd.h>

#include <nanovdb/util/OpenToNanoVDB.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <sstream>

#include "renderer/volume/nano_density_grid.h"

namespace vesper {
namespace {

namespace fs = std::filesystem;

void init_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

std::string quoted(const fs::path& p) { return p.string(); }

// Opens a file for reading; every failure becomes "cannot open <file>: <reason>".
std::unique_ptr<openvdb::io::File> open_file(const fs::path& file) {
  init_openvdb();
  std::error_code ec;
  if (!fs::exists(file, ec)) throw VdbError("cannot open " + quoted(file) + ": no such file");
  if (fs::is_directory(file, ec))
    throw VdbError("cannot open " + quoted(file) + ": is a directory");
  auto f = std::make_unique<openvdb::io::File>(file.string());
  try {
    f->open(/*delayLoad=*/false);
  } catch (const std::exception& e) {
    throw VdbError("cannot open " + quoted(file) + ": " + e.what());
  }
  return f;
}

// "density (float), temperature (float)"
std::string grid_listing(openvdb::io::File& f) {
  openvdb::GridPtrVecPtr grids = f.readAllGridMetadata();
  std::string s;
  for (const auto& g : *grids) {
    if (!s.empty()) s += ", ";
    s += g->getName() + " (" + g->valueType() + ")";
  }
  return s.empty() ? "no grids" : s;
}

std::string coord_str(const openvdb::Coord& c) {
  std::ostringstream s;
  s << "(" << c.x() << ", " << c.y() << ", " << c.z() << ")";
  return s.str();
}

std::string num_str(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

// OpenVDB maps row vectors: world = [i j k 1] * M, translation in row 3.
Transform to_transform(const openvdb::math::Transform& tf) {
  const openvdb::Mat4d m = tf.baseMap()->getAffineMap()->getMat4();
  Matrix4 a;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a(r, c) = m(c, r);
    a(r, 3) = m(3, r);
  }
  return Transform(a);
}

IndexBox to_box(const openvdb::CoordBBox& b) {
  IndexBox box;
  if (b.empty()) return box;
  box.min = {b.min().x(), b.min().y(), b.min().z()};
  box.max = {b.max().x(), b.max().y(), b.max().z()};
  return box;
}

template <typename GridT>
void scalar_range(const GridT& grid, VdbGridInfo& info) {
  bool first = true;
  for (auto it = grid.cbeginValueOn(); it; ++it) {
    const double v = double(*it);
    if (first) {
      info.min_value = info.max_value = v;
      first = false;
    } else {
      info.min_value = std::min(info.min_value, v);
      info.max_value = std::max(info.max_value, v);
    }
  }
  info.has_range = !first;
  info.background = double(grid.background());
}

}  // namespace

std::vector<std::string> list_vdb_grids(const fs::path& file) {
  auto f = open_file(file);
  std::vector<std::string> out;
  try {
    const openvdb::GridPtrVecPtr grids =
        f->readAllGridMetadata();  // keep alive: range-for over *temp dangles
    for (const auto& g : *grids) out.push_back(g->getName() + ": " + g->valueType());
  } catch (const std::exception& e) {
    throw VdbError(quoted(file) + ": cannot read grid metadata: " + e.what());
  }
  return out;
}

std::vector<VdbGridInfo> describe_vdb_grids(const fs::path& file) {
  auto f = open_file(file);
  std::vector<VdbGridInfo> out;
  try {
    const openvdb::GridPtrVecPtr metas = f->readAllGridMetadata();
    for (const auto& meta : *metas) {
      openvdb::GridBase::Ptr g = f->readGrid(meta->getName());
      VdbGridInfo info;
      info.name = g->getName();
      info.value_type = g->valueType();
      info.grid_class = openvdb::GridBase::gridClassToString(g->getGridClass());
      info.active_voxels = g->activeVoxelCount();
      info.active_box = to_box(g->evalActiveVoxelBoundingBox());
      info.linear_transform = g->transform().isLinear();
      if (info.linear_transform) info.index_to_world = to_transform(g->transform());
      if (auto fg = openvdb::GridBase::grid<openvdb::FloatGrid>(g))
        scalar_range(*fg, info);
      else if (auto dg = openvdb::GridBase::grid<openvdb::DoubleGrid>(g))
        scalar_range(*dg, info);
      else if (auto ig = openvdb::GridBase::grid<openvdb::Int32Grid>(g))
        scalar_range(*ig, info);
      out.push_back(std::move(info));
    }
  } catch (const VdbError&) {
    throw;
  } catch (const std::exception& e) {
    throw VdbError(quoted(file) + ": cannot read grids: " + e.what());
  }
  return out;
}

std::shared_ptr<const DensityGrid> load_vdb_grid(const fs::path& file, const std::string& grid_name,
                                                 bool reject_negative) {
  auto f = open_file(file);
  const std::string where = quoted(file) + ": grid '" + grid_name + "'";
  openvdb::GridBase::Ptr base;
  try {
    if (!f->hasGrid(grid_name))
      throw VdbError(quoted(file) + ": no grid named '" + grid_name +
                     "'; the file has: " + grid_listing(*f));
    base = f->readGrid(grid_name);
  } catch (const VdbError&) {
    throw;
  } catch (const std::exception& e) {
    throw VdbError(where + ": cannot read: " + e.what());
  }
  openvdb::FloatGrid::Ptr grid = openvdb::GridBase::grid<openvdb::FloatGrid>(base);
  if (!grid)
    throw VdbError(where + " has value type " + base->valueType() +
                   ", a float grid is needed; the file has: " + grid_listing(*f));

  const openvdb::math::Transform& tf = grid->transform();
  if (!tf.isLinear())
    throw VdbError(where + " has a non-linear index-to-world transform (" + tf.mapType() +
                   "); only affine (linear) transforms are supported");

  const float bg = grid->background();
  if (!std::isfinite(bg)) throw VdbError(where + ": background value is " + num_str(bg));
  if (bg != 0.0f)
    throw VdbError(
        where + ": background value is " + num_str(bg) +
        ", but a density must be 0 outside its active voxels (a level set? convert it to a fog "
        "volume first, e.g. vdb_tool -read in.vdb -ls2fog -write out.vdb)");
  if (grid->activeVoxelCount() == 0) throw VdbError(where + " has no active voxels");

  float max_value = 0.0f;
  for (auto it = grid->cbeginValueOn(); it; ++it) {
    const float v = *it;
    if (!std::isfinite(v))
      throw VdbError(where + ": " + (it.isVoxelValue() ? "voxel " : "tile at ") +
                     coord_str(it.getCoord()) + " is " + num_str(v) +
                     " (NaN/Inf values are not allowed)");
    if (reject_negative && v < 0.0f)
      throw VdbError(where + ": " + (it.isVoxelValue() ? "voxel " : "tile at ") +
                     coord_str(it.getCoord()) + " is negative (" + num_str(v) + ")");
    max_value = std::max(max_value, v);
  }
  // Inactive voxels inside leaves may hold stale values (even NaN); the
  // DensityGrid contract is 0 outside the active voxels, so make them 0.
  for (auto it = grid->tree().beginValueOff(); it; ++it)
    if (*it != 0.0f) it.setValue(0.0f);

  const IndexBox box = to_box(grid->evalActiveVoxelBoundingBox());
  nanovdb::GridHandle<nanovdb::HostBuffer> handle;
  try {
    handle = nanovdb::openToNanoVDB(*grid);
  } catch (const std::exception& e) {
    throw VdbError(where + ": conversion to NanoVDB failed: " + e.what());
  }
  return std::make_shared<NanoDensityGrid>(std::move(handle), grid_name, to_transform(tf), box,
                                           max_value);
}

void write_vdb_fog_volume(const DenseVolume& volume, const std::string& grid_name,
                          const fs::path& file, float cutoff) {
  init_openvdb();
  const std::string where = "cannot write " + quoted(file);
  if (volume.nx <= 0 || volume.ny <= 0 || volume.nz <= 0)
    throw VdbError(where + ": volume dimensions must be positive");
  if (volume.values.size() != size_t(volume.nx) * size_t(volume.ny) * size_t(volume.nz))
    throw VdbError(where + ": volume has " + std::to_string(volume.values.size()) +
                   " values, expected nx*ny*nz");
  if (!(volume.voxel_size > 0) || !std::isfinite(volume.voxel_size))
    throw VdbError(where + ": voxel size must be positive and finite");
  if (!std::isfinite(volume.origin.x) || !std::isfinite(volume.origin.y) ||
      !std::isfinite(volume.origin.z))
    throw VdbError(where + ": origin must be finite");
  if (grid_name.empty()) throw VdbError(where + ": empty grid name");

  // Values below cutoff stay inactive background (0). The test is !(v < cutoff)
  // so a NaN is written as an active voxel: the writer stores what it is given,
  // the loader is the one that validates (tests rely on this to make bad files).
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  {
    auto acc = grid->getAccessor();
    size_t n = 0;
    for (int k = 0; k < volume.nz; ++k)
      for (int j = 0; j < volume.ny; ++j)
        for (int i = 0; i < volume.nx; ++i, ++n) {
          const float v = volume.values[n];
          if (!(v < cutoff)) acc.setValue(openvdb::Coord(i, j, k), v);
        }
  }
  grid->setName(grid_name);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setCreator("vesper " VESPER_VERSION);
  openvdb::math::Transform::Ptr tf =
      openvdb::math::Transform::createLinearTransform(volume.voxel_size);
  tf->postTranslate(openvdb::Vec3d(volume.origin.x, volume.origin.y, volume.origin.z));
  grid->setTransform(tf);

  // Atomic: write a temporary file beside the target, then rename over it.
  static std::atomic<unsigned> counter{0};
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  const fs::path tmp = dir / (file.filename().string() + ".tmp-" + std::to_string(::getpid()) +
                              "-" + std::to_string(counter++));
  try {
    openvdb::io::File out(tmp.string());
    out.write({grid});
    out.close();
    fs::rename(tmp, file);
  } catch (const std::exception& e) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw VdbError(where + ": " + e.what());
  }
}

}  // namespace vesper
