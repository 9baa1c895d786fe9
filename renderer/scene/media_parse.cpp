// Parses one entry of "media": a homogeneous medium (optionally bounded by a
// box) or a heterogeneous medium from an OpenVDB grid (with optional emission).
// Every cheap value is validated before any .vdb file is read.
#include <new>

#include "renderer/scene/scene_loader.h"
#include "renderer/scene/scene_parse.h"
#include "renderer/volume/vdb_io.h"

namespace vesper {
namespace {

constexpr std::string_view kMediumTypes[] = {"homogeneous", "vdb"};

// Henyey-Greenstein g = +-1 is a delta phase function with an infinite pdf.
const Range kAsymmetry = Range::open(-1, 1);

}  // namespace

BoxDesc parse_box(JsonReader node) {
  node.expect_object();
  node.allow_keys({"min", "max"});
  BoxDesc box{read_vec3(node, "min"), read_vec3(node, "max")};
  for (int i = 0; i < 3; ++i) {
    if (!(box.min[i] < box.max[i])) {
      static constexpr const char* kAxis[] = {"x", "y", "z"};
      node.fail("expected min < max on every axis, got min." + std::string(kAxis[i]) + " = " +
                describe_json(box.min[i]) + " and max." + kAxis[i] + " = " +
                describe_json(box.max[i]));
    }
  }
  return box;
}

namespace {

HomogeneousMediumDesc parse_homogeneous(JsonReader& node) {
  node.allow_keys({"type", "sigma_a", "sigma_s", "g", "bounds"});
  HomogeneousMediumDesc m;
  m.sigma_a = read_rgb(node, "sigma_a", Rgb(0.f), Range::non_negative());
  m.sigma_s = read_rgb(node, "sigma_s", Range::non_negative());
  m.g = node.number("g", 0.0, kAsymmetry);
  if (const auto bounds = node.optional_child("bounds")) m.bounds = parse_box(*bounds);
  return m;
}

// Loads one grid; a VdbError becomes a SceneError at `grid_key` when the file
// itself is readable (missing grid, wrong type, bad voxels), else at `file_key`.
std::shared_ptr<const DensityGrid> load_grid(const JsonReader& node,
                                             const std::filesystem::path& path,
                                             const std::string& grid, std::string_view grid_key) {
  try {
    return load_vdb_grid(path, grid, /*reject_negative=*/true);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    // Only on the error path: tell "the file is unreadable" from "the grid is wrong".
    bool file_readable = true;
    try {
      list_vdb_grids(path);
    } catch (const std::exception&) {
      file_readable = false;
    }
    node.fail_key(file_readable ? grid_key : std::string_view("file"), e.what());
  }
}

// Rendering maps render space to the grid's index space in float: the
// grid's own transform combined with `transform` must stay far inside the
// float range (a translate of 1e308 overflowed it), and be invertible.
}  // namespace

void check_grid_transform(JsonReader& node, const Transform& transform, const DensityGrid& grid) {
  constexpr double kLimit = 1e30;
  if (!transform_fits(transform * grid.index_to_world(), kLimit))
    node.fail_key(node.has("transform") ? "transform" : "file",
                  "expected the grid '" + grid.name() +
                      "' with its transform to map voxels to world positions within 1e30 "
                      "(and back): its matrix or inverse is larger or not finite");
}

namespace {

VdbMediumDesc parse_vdb(JsonReader& node, SceneParseContext& ctx) {
  node.allow_keys({"type", "file", "grid", "density_scale", "sigma_a", "sigma_s", "g", "transform",
                   "emission_grid", "emission_scale", "emission_color"});
  VdbMediumDesc m;
  const JsonReader file = node.child("file");
  const std::filesystem::path path = ctx.resolve(file);
  m.file = path.string();
  if (const auto grid = node.optional_child("grid")) m.grid = grid->as_string();
  m.density_scale = node.number("density_scale", m.density_scale, Range::non_negative());
  m.sigma_a = read_rgb(node, "sigma_a", m.sigma_a, Range::non_negative());
  m.sigma_s = read_rgb(node, "sigma_s", m.sigma_s, Range::non_negative());
  m.g = node.number("g", m.g, kAsymmetry);
  if (const auto transform = node.optional_child("transform")) {
    m.transform = parse_transform(*transform);
  }
  if (const auto emission_grid = node.optional_child("emission_grid")) {
    m.emission_grid = emission_grid->as_string();
  }
  m.emission_scale = node.number("emission_scale", m.emission_scale, Range::non_negative());
  m.emission_color = read_rgb(node, "emission_color", m.emission_color, Range::non_negative());
  if (m.emission_scale > 0 && m.emission_grid.empty()) {
    node.fail_key("emission_scale",
                  "emission_scale > 0 needs 'emission_grid' (the grid whose values emit), got "
                  "emission_scale " +
                      describe_json(m.emission_scale) + " and no emission_grid");
  }

  // The file last: everything above is cheap, a .vdb load is not.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    file.fail("VDB file not found: '" + path.string() + "'");
  }
  m.density = load_grid(node, path, m.grid, "grid");
  if (!m.emission_grid.empty())
    m.emission = load_grid(node, path, m.emission_grid, "emission_grid");
  check_grid_transform(node, m.transform, *m.density);
  if (m.emission) check_grid_transform(node, m.transform, *m.emission);
  ctx.referenced_files.push_back(path);
  return m;
}

}  // namespace

MediumDesc parse_medium(JsonReader node, const std::string& name, SceneParseContext& ctx) {
  if (name.empty()) node.fail("expected a non-empty medium name");
  node.expect_object();
  MediumDesc medium;
  medium.name = name;
  if (node.enumeration("type", kMediumTypes) == 0) {
    medium.medium = parse_homogeneous(node);
  } else {
    medium.medium = parse_vdb(node, ctx);
  }
  return medium;
}

}  // namespace vesper
