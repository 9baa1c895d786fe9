// Shape names (Cryptomatte's object names): an optional unique "name", else
// the type and index ("quad0", "sphere1", "mesh2"); a name two shapes share
// is refused at the second one's JSON path.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "renderer/scene/scene_loader.h"
#include "tests/renderer/minimal_scene.h"

namespace vesper::test {
namespace {

using nlohmann::json;

json with_shapes(const char* shapes) {
  json doc = minimal_scene();
  doc["shapes"] = json::parse(shapes);
  return doc;
}

constexpr char kQuad[] =
    R"({"type": "quad", "corner": [0,0,0], "edge1": [1,0,0], "edge2": [0,1,0], "material": "m")";
constexpr char kSphere[] = R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m")";
constexpr char kMesh[] =
    R"({"type": "mesh", "positions": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,2], "material": "m")";

std::string error_of(const json& doc) {
  try {
    parse_scene(doc, "s.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SceneShapeNames, DefaultIsTypeAndIndex) {
  const std::string shapes = std::string("[") + kQuad + "}, " + kSphere + R"(, "name": "ball"}, )" +
                             kMesh + "}, " + kSphere + "}]";
  const SceneDescription d = parse_scene(with_shapes(shapes.c_str()), "s.json");
  ASSERT_EQ(d.shapes.size(), 4u);
  EXPECT_EQ(d.shapes[0].name, "quad0");
  EXPECT_EQ(d.shapes[1].name, "ball");
  EXPECT_EQ(d.shapes[2].name, "mesh2");
  EXPECT_EQ(d.shapes[3].name, "sphere3");
  // A description built in code (no names) gets the same defaults.
  SceneDescription built = d;
  for (ShapeDesc& s : built.shapes) s.name.clear();
  EXPECT_EQ(shape_name(built, 0), "quad0");
  EXPECT_EQ(shape_name(built, 3), "sphere3");
}

TEST(SceneShapeNames, DuplicatesAreRefusedWithTheirPaths) {
  const std::string twice =
      std::string("[") + kQuad + R"(, "name": "wall"}, )" + kSphere + R"(, "name": "wall"}])";
  EXPECT_EQ(error_of(with_shapes(twice.c_str())),
            "s.json: /shapes/1/name: expected a unique shape name, got \"wall\", the name of "
            "/shapes/0 already");
  // An explicit name equal to another shape's default name.
  const std::string clash = std::string("[") + kQuad + R"(, "name": "sphere1"}, )" + kSphere + "}]";
  EXPECT_EQ(error_of(with_shapes(clash.c_str())),
            "s.json: /shapes/1: its default name \"sphere1\" is the name of /shapes/0 already: "
            "give one of them another \"name\"");
  const std::string empty = std::string("[") + kQuad + R"(, "name": ""}])";
  EXPECT_NE(error_of(with_shapes(empty.c_str())).find("/shapes/0/name"), std::string::npos);
  const std::string number = std::string("[") + kQuad + R"(, "name": 3}])";
  EXPECT_NE(error_of(with_shapes(number.c_str())).find("/shapes/0/name"), std::string::npos);
}

// Names are part of the scene's content hash: renaming a shape changes the
// Cryptomatte ids, so the farm does not reuse a frame rendered before.
TEST(SceneShapeNames, NamesArePartOfTheHash) {
  const std::string shapes = std::string("[") + kQuad + "}]";
  const json doc = with_shapes(shapes.c_str());
  json named = doc;
  named["shapes"][0]["name"] = "floor";
  EXPECT_NE(parse_scene(named, "s.json").content_hash, parse_scene(doc, "s.json").content_hash);
}

}  // namespace
}  // namespace vesper::test
