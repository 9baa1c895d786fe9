// Parses one entry of "shapes": quad, sphere or mesh (from a file or inline).
#include <limits>
#include <map>

#include "renderer/scene/mesh_loader.h"
#include "renderer/scene/scene_parse.h"

namespace vesper {
namespace {

constexpr std::string_view kShapeTypes[] = {"quad", "sphere", "mesh"};

std::vector<Vec3d> parse_positions(JsonReader node) {
  const std::vector<double> flat = node.as_number_array();
  if (flat.empty() || flat.size() % 3 != 0) {
    node.fail("expected a non-empty flat array of x, y, z numbers (length a multiple of 3), got " +
              std::to_string(flat.size()) + " numbers");
  }
  if (flat.size() / 3 > std::numeric_limits<uint32_t>::max()) node.fail("too many vertices");
  std::vector<Vec3d> positions(flat.size() / 3);
  for (size_t i = 0; i < positions.size(); ++i) {
    positions[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  }
  return positions;
}

std::vector<std::array<uint32_t, 3>> parse_indices(JsonReader node, size_t vertex_count) {
  node.expect_array();
  const nlohmann::json& flat = node.json();
  if (flat.empty() || flat.size() % 3 != 0) {
    node.fail("expected a non-empty flat array of vertex indices (length a multiple of 3), got " +
              std::to_string(flat.size()) + " elements");
  }
  std::vector<std::array<uint32_t, 3>> triangles(flat.size() / 3);
  for (size_t i = 0; i < flat.size(); ++i) {
    const nlohmann::json& e = flat[i];
    uint64_t index;
    // Fast path for the common case; anything unusual gets the full check and message.
    if (e.is_number_unsigned() && e.get<uint64_t>() < vertex_count) {
      index = e.get<uint64_t>();
    } else {
      index = uint64_t(node.element(i).as_integer(0, int64_t(vertex_count) - 1));
    }
    triangles[i / 3][i % 3] = uint32_t(index);
  }
  return triangles;
}

MeshShapeDesc parse_mesh(JsonReader& node, SceneParseContext& ctx) {
  const auto file = node.optional_child("file");
  const auto positions = node.optional_child("positions");
  const auto indices = node.optional_child("indices");
  const auto transform = node.optional_child("transform");
  if (file && (positions || indices)) {
    node.fail("use either 'file' or 'positions' + 'indices', not both");
  }
  MeshShapeDesc mesh;
  if (file) {
    const std::filesystem::path path = ctx.resolve(*file);
    mesh = load_mesh_file(path, ctx.file, file->path());
    ctx.referenced_files.push_back(path);
  } else {
    if (!positions && !indices) node.fail("expected either 'file' or 'positions' + 'indices'");
    if (!positions) node.fail("missing required key 'positions' (inline meshes need both)");
    if (!indices) node.fail("missing required key 'indices' (inline meshes need both)");
    mesh.positions = parse_positions(*positions);
    mesh.triangles = parse_indices(*indices, mesh.positions.size());
    mesh.source = "inline mesh at " + node.path();
  }
  if (transform) {
    const Transform t = parse_transform(*transform);
    for (Vec3d& p : mesh.positions) {
      p = t.apply_point(p);
      if (!is_finite(p)) transform->fail("transformed vertex positions overflow to infinity");
    }
  }
  return mesh;
}

}  // namespace

ShapeDesc parse_shape(JsonReader node, SceneParseContext& ctx) {
  node.expect_object();
  ShapeDesc shape;
  switch (node.enumeration("type", kShapeTypes)) {
    case 0: {
      node.allow_keys({"type", "corner", "edge1", "edge2", "material", "name"});
      shape.material = ctx.material(node, "material");
      // Zero-area quads are accepted: they are simply invisible.
      shape.geometry = QuadShapeDesc{read_vec3(node, "corner"), read_vec3(node, "edge1"),
                                     read_vec3(node, "edge2")};
      break;
    }
    case 1: {
      node.allow_keys({"type", "center", "radius", "material", "name"});
      shape.material = ctx.material(node, "material");
      shape.geometry =
          SphereShapeDesc{read_vec3(node, "center"), node.number("radius", Range::positive())};
      break;
    }
    default: {
      node.allow_keys({"type", "file", "positions", "indices", "transform", "material", "name"});
      shape.material = ctx.material(node, "material");  // before a possibly slow mesh load
      shape.geometry = parse_mesh(node, ctx);
      break;
    }
  }
  if (const auto name = node.optional_child("name")) shape.name = name->as_string();
  return shape;
}

void name_shapes(const JsonReader& shapes, SceneDescription& scene) {
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < scene.shapes.size(); ++i) {
    const bool explicit_name = !scene.shapes[i].name.empty();
    const std::string name = shape_name(scene, i);
    const auto [at, fresh] = seen.emplace(name, i);
    if (!fresh) {
      const std::string first = json_pointer_append(shapes.path(), at->second);
      const JsonReader shape = shapes.element(i);
      if (explicit_name)
        shape.fail_key("name", "expected a unique shape name, got \"" + name + "\", the name of " +
                                   first + " already");
      shape.fail("its default name \"" + name + "\" is the name of " + first +
                 " already: give one of them another \"name\"");
    }
    scene.shapes[i].name = name;
  }
}

}  // namespace vesper
