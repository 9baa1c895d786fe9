// Every value the issue lists as keyable (camera, shape and medium transforms,
// lights, media, material albedo) loads per frame: one table, one row a value.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <variant>

#include "renderer/scene/scene_loader.h"
#include "tests/renderer/minimal_scene.h"
#include "tests/renderer/vdb_fixtures.h"

namespace vesper {
namespace {

using nlohmann::json;

// A scene with one of everything that has keyable values.
json rich_scene(const std::string& vdb_file) {
  json doc = test::minimal_scene();
  doc["shapes"] = json::parse(R"([{"type": "mesh", "material": "m",
      "positions": [1, 0, 0, 0, 1, 0, 0, 0, 1], "indices": [0, 1, 2],
      "transform": {"translate": [0, 0, 0], "scale": 1, "rotate": {"axis": [0, 0, 1], "angle": 0}}}])");
  doc["lights"] = json::parse(R"([
      {"type": "quad", "corner": [0, 2, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "radiance": [1, 1, 1]},
      {"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]},
      {"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "intensity": [1, 1, 1],
       "cone_angle": 30, "falloff_start": 20},
      {"type": "sun", "direction": [0, 1, 0], "irradiance": [1, 1, 1]},
      {"type": "environment", "radiance": [1, 1, 1]}])");
  doc["media"] = json::parse(R"({
      "fog": {"type": "homogeneous", "sigma_s": [0.1, 0.1, 0.1]},
      "smoke": {"type": "vdb", "file": ")" +
                             vdb_file + R"(", "density_scale": 1, "sigma_a": [0, 0, 0],
                "emission_grid": "density", "emission_color": [1, 1, 1],
                "transform": {"translate": [0, 0, 0]}}})");
  return doc;
}

template <typename T>
const T& light(const SceneDescription& s, size_t i) {
  return std::get<T>(s.lights.at(i).light);
}
const VdbMediumDesc& smoke(const SceneDescription& s) {
  return std::get<VdbMediumDesc>(s.media.at(1).medium);  // "smoke" after "fog"
}

struct KeyedRow {
  std::string pointer;  // the value replaced by keys [[1, a], [3, b]]
  json a, b;
  std::function<double(const SceneDescription&)> probe;
  double at_a, at_b;  // probe at frames 1 and 3
};

std::vector<KeyedRow> rows() {
  const auto mesh_x = [](const SceneDescription& s) {
    return std::get<MeshShapeDesc>(s.shapes.at(0).geometry).positions.at(0).x;
  };
  return {
      {"/camera/from", {0, 0, 4}, {2, 0, 4}, [](auto& s) { return s.camera.from.x; }, 0, 2},
      {"/camera/to", {0, 0, 0}, {0, 1, 0}, [](auto& s) { return s.camera.to.y; }, 0, 1},
      {"/camera/up", {0, 1, 0}, {1, 1, 0}, [](auto& s) { return s.camera.up.x; }, 0, 1},
      {"/camera/fov", 20, 60, [](auto& s) { return s.camera.fov_degrees; }, 20, 60},
      {"/shapes/0/transform/translate", {0, 0, 0}, {4, 0, 0}, mesh_x, 1, 5},
      {"/shapes/0/transform/scale", 1, 3, mesh_x, 1, 3},
      {"/shapes/0/transform/rotate/angle", 0, 90, mesh_x, 1, 0},
      {"/lights/0/radiance",
       {1, 1, 1},
       {5, 1, 1},
       [](auto& s) { return light<QuadLightDesc>(s, 0).radiance.r; },
       1,
       5},
      {"/lights/1/position",
       {0, 1, 0},
       {2, 1, 0},
       [](auto& s) { return light<PointLightDesc>(s, 1).position.x; },
       0,
       2},
      {"/lights/1/intensity",
       {1, 1, 1},
       {1, 3, 1},
       [](auto& s) { return light<PointLightDesc>(s, 1).intensity.g; },
       1,
       3},
      {"/lights/2/direction",
       {0, -1, 0},
       {1, 0, 0},
       [](auto& s) { return light<SpotLightDesc>(s, 2).direction.x; },
       0,
       1},
      {"/lights/3/direction",
       {0, 1, 0},
       {0, 0, 1},
       [](auto& s) { return light<SunLightDesc>(s, 3).direction.z; },
       0,
       1},
      {"/lights/4/radiance",
       {1, 1, 1},
       {1, 1, 0.5},
       [](auto& s) { return light<EnvironmentLightDesc>(s, 4).radiance.b; },
       1,
       0.5},
      {"/media/fog/sigma_s",
       {0.1, 0.1, 0.1},
       {0.5, 0.1, 0.1},
       [](auto& s) { return std::get<HomogeneousMediumDesc>(s.media.at(0).medium).sigma_s.r; },
       0.1,
       0.5},
      {"/media/smoke/density_scale", 1, 4, [](auto& s) { return smoke(s).density_scale; }, 1, 4},
      {"/media/smoke/sigma_a",
       {0, 0, 0},
       {0, 0, 2},
       [](auto& s) { return smoke(s).sigma_a.b; },
       0,
       2},
      {"/media/smoke/emission_color",
       {1, 1, 1},
       {1, 0.25, 1},
       [](auto& s) { return smoke(s).emission_color.g; },
       1,
       0.25},
      {"/media/smoke/transform/translate",
       {0, 0, 0},
       {0, 3, 0},
       [](auto& s) { return smoke(s).transform.matrix()(1, 3); },
       0,
       3},
      {"/materials/m/albedo",
       {0.8, 0.8, 0.8},
       {0.2, 0.8, 0.8},
       [](auto& s) { return std::get<DiffuseMaterialDesc>(s.materials.at(0)).albedo.r; },
       0.8,
       0.2},
  };
}

TEST(SceneKeyedValues, EveryKeyableValueChangesPerFrameAndHoldsOutsideItsKeys) {
  test::VdbTempDir dir;
  test::write_volume(dir, "smoke.vdb", test::make_volume(4, 4, 4, [](int, int, int) { return 1; }));
  const json still = rich_scene("smoke.vdb");
  const auto file = dir / "shot.json";
  for (const KeyedRow& row : rows()) {
    SCOPED_TRACE(row.pointer);
    json doc = still;
    doc[json::json_pointer(row.pointer)] = json{{"keys", {{1, row.a}, {3, row.b}}}};
    auto at = [&](double frame) {
      return row.probe(parse_scene(doc, file, SceneLoadOptions{.frame = frame}));
    };
    EXPECT_NEAR(at(1), row.at_a, 1e-6);
    EXPECT_NEAR(at(3), row.at_b, 1e-6);
    // Between the keys strictly between the values; held before and after.
    const double mid = at(2), lo = std::min(row.at_a, row.at_b), hi = std::max(row.at_a, row.at_b);
    EXPECT_GT(mid, lo + 1e-6);
    EXPECT_LT(mid, hi - 1e-6);
    EXPECT_NEAR(at(-5), row.at_a, 1e-6);
    EXPECT_NEAR(at(40), row.at_b, 1e-6);
  }
}

TEST(SceneKeyedValues, AnErrorInAKeyedValueSaysTheFrame) {
  json doc = test::minimal_scene();
  doc["camera"]["fov"] = json::parse(R"({"keys": [[1, 30], [3, 190]]})");
  try {
    parse_scene(doc, "shot.json", SceneLoadOptions{.frame = 3});
    FAIL() << "fov 190 at frame 3 was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.json_path(), "/camera/fov");
    EXPECT_NE(e.message().find("(keyed; at frame 3)"), std::string::npos) << e.what();
  }
  // Inside a keyed vector: the error names the component, and still the frame.
  doc = test::minimal_scene();
  doc["camera"]["up"] = json::parse(R"({"keys": [[1, [0, 1, 0]], [2, [0, 0, 4]]]})");
  try {
    parse_scene(doc, "shot.json", SceneLoadOptions{.frame = 2});
    FAIL() << "an up vector parallel to the view was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(e.message().find("(keyed; at frame 2)"), std::string::npos) << e.what();
  }
  // A still value's error says nothing of frames.
  doc = test::minimal_scene();
  doc["camera"]["fov"] = 190;
  try {
    parse_scene(doc, "shot.json", SceneLoadOptions{.frame = 3});
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.message().find("keyed"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesper
