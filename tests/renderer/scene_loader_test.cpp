// The scene loader on valid input: field values, defaults, meshes from files,
// transform maths, environment images, media (homogeneous and OpenVDB), layers
// and AOVs, the content hash.
#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "renderer/scene/environment_image.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/volume/vdb_io.h"
#include "tests/common/temp_dir.h"
#include "tests/renderer/minimal_scene.h"

namespace vesper {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kDataDir(VESPER_TEST_DATA_DIR);

void expect_near(const Vec3d& a, const Vec3d& b, double eps = 1e-12) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

using test::minimal_scene;

using test::TempDir;

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

TEST(SceneLoader, ValidSceneFields) {
  const SceneDescription s = load_scene(kDataDir / "valid_scene.json");
  EXPECT_EQ(s.file, kDataDir / "valid_scene.json");
  expect_near(s.camera.from, {0, 1, 3.5});
  expect_near(s.camera.to, {0, 1, 0});
  EXPECT_EQ(s.camera.fov_degrees, 40);
  EXPECT_EQ(s.camera.aperture, 0.05);
  EXPECT_EQ(s.camera.focus_distance, 3);
  EXPECT_EQ(s.film.width, 320);
  EXPECT_EQ(s.film.height, 240);
  EXPECT_EQ(s.film.filter, FilterType::Gaussian);
  EXPECT_EQ(s.render.spp, 64);
  EXPECT_EQ(s.render.max_depth, 5);
  EXPECT_EQ(s.render.seed, 7u);
  EXPECT_EQ(s.render.aovs, (std::vector<Aov>{Aov::Normal, Aov::Albedo}));

  // Materials come in name order; shapes refer to them by index.
  ASSERT_EQ(s.material_names, (std::vector<std::string>{"copper", "glass", "gold", "green",
                                                        "plastic", "red", "white"}));
  const auto& copper = std::get<ConductorMaterialDesc>(s.materials[0]);
  EXPECT_EQ(copper.eta, Rgb(0.2f, 1.1f, 1.2f));
  EXPECT_EQ(std::get<DielectricMaterialDesc>(s.materials[1]).ior, 1.33);
  EXPECT_EQ(std::get<DielectricMaterialDesc>(s.materials[1]).roughness, 0);
  EXPECT_EQ(std::get<ConductorMaterialDesc>(s.materials[2]).roughness, 0.3);
  EXPECT_EQ(std::get<ConductorMaterialDesc>(s.materials[2]).k, ConductorMaterialDesc{}.k);
  EXPECT_EQ(std::get<DiffuseMaterialDesc>(s.materials[3]).albedo, Rgb(0.8f));  // default
  const auto& plastic = std::get<PrincipledMaterialDesc>(s.materials[4]);
  EXPECT_EQ(plastic.base_color, Rgb(0.1f, 0.2f, 0.9f));
  EXPECT_EQ(plastic.metallic, 0.25);
  EXPECT_EQ(plastic.roughness, 1);

  ASSERT_EQ(s.shapes.size(), 7u);
  EXPECT_EQ(s.material_names[s.shapes[0].material], "white");
  EXPECT_EQ(s.material_names[s.shapes[1].material], "red");
  const auto& quad = std::get<QuadShapeDesc>(s.shapes[2].geometry);
  expect_near(quad.corner, {1, 0, -1});
  expect_near(quad.edge2, {0, 2, 0});
  const auto& sphere = std::get<SphereShapeDesc>(s.shapes[3].geometry);
  EXPECT_EQ(sphere.radius, 0.3);
  EXPECT_EQ(s.material_names[s.shapes[3].material], "glass");
  EXPECT_EQ(std::get<MeshShapeDesc>(s.shapes[4].geometry).triangles.size(), 6u);
  EXPECT_EQ(std::get<MeshShapeDesc>(s.shapes[5].geometry).triangles.size(), 3u);

  ASSERT_EQ(s.lights.size(), 6u);
  const auto& ql = std::get<QuadLightDesc>(s.lights[0].light);
  EXPECT_EQ(ql.radiance, Rgb(17, 12, 4));
  EXPECT_EQ(s.lights[0].group, "ceiling");
  EXPECT_EQ(std::get<PointLightDesc>(s.lights[1].light).intensity, Rgb(2.f));
  EXPECT_EQ(s.lights[1].group, "");
  const auto& spot = std::get<SpotLightDesc>(s.lights[2].light);
  expect_near(spot.direction, {0, -1, 0});  // normalized
  EXPECT_EQ(spot.cone_angle, 30);
  EXPECT_EQ(spot.falloff_start, 20);
  EXPECT_EQ(s.lights[2].group, "spots");
  const auto& spot2 = std::get<SpotLightDesc>(s.lights[3].light);
  expect_near(spot2.direction, {std::sqrt(0.5), -std::sqrt(0.5), 0});
  EXPECT_EQ(spot2.falloff_start, 45);  // defaults to cone_angle
  const auto& sun = std::get<SunLightDesc>(s.lights[4].light);
  expect_near(sun.direction, {0, 0.6, 0.8});
  EXPECT_EQ(sun.angle, 0.53);  // the real sun's angular diameter by default
  const auto& env = std::get<EnvironmentLightDesc>(s.lights[5].light);
  EXPECT_EQ(env.radiance, Rgb(0.1f, 0.2f, 0.3f));
  EXPECT_FALSE(env.image);

  EXPECT_EQ(s.content_hash.size(), 16u);
}

TEST(SceneLoader, Defaults) {
  const SceneDescription s = parse_scene(minimal_scene(), "x/minimal.json");
  EXPECT_EQ(s.camera.aperture, 0);
  EXPECT_DOUBLE_EQ(s.camera.focus_distance, 4);  // |to - from|
  EXPECT_EQ(s.film.filter, FilterType::Box);
  EXPECT_EQ(s.render.max_depth, 8);
  EXPECT_EQ(s.render.seed, 0u);
  EXPECT_TRUE(s.render.aovs.empty());
  EXPECT_TRUE(s.shapes.empty());
  EXPECT_TRUE(s.lights.empty());  // a scene without lights is allowed
  EXPECT_TRUE(s.media.empty());   // media are optional
}

TEST(SceneLoader, ErrorMessageFormat) {
  json doc = minimal_scene();
  doc["shapes"] =
      json::parse(R"([{"type": "sphere", "center": [0,0,0], "radius": -1, "material": "m"}])");
  try {
    parse_scene(doc, "scenes/x.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "scenes/x.json: /shapes/0/radius: expected a positive number, got -1");
    EXPECT_EQ(e.json_path(), "/shapes/0/radius");
    EXPECT_EQ(e.message(), "expected a positive number, got -1");
  }
}

// load_scene stops 1e999 at parse time; a document built in code can still hold inf/NaN.
TEST(SceneLoader, NonFiniteNumbersInADocumentAreRejected) {
  for (double bad : {std::numeric_limits<double>::infinity(), std::nan("")}) {
    json doc = minimal_scene();
    doc["shapes"] = json::array(
        {{{"type", "sphere"}, {"center", {0, bad, 0}}, {"radius", 1}, {"material", "m"}}});
    try {
      parse_scene(doc, "s.json");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.json_path(), "/shapes/0/center/1");
      EXPECT_NE(e.message().find("expected a finite number"), std::string::npos) << e.what();
    }
  }
}

TEST(SceneLoader, MissingSceneFile) {
  try {
    load_scene(kDataDir / "no_such_scene.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_scene.json"), std::string::npos);
  }
}

TEST(SceneLoader, MaterialNamesAreEscapedInPaths) {
  json doc = minimal_scene();
  doc["materials"]["a/b"] = json::parse(R"({"type": "diffuse", "albedo": [2, 0, 0]})");
  try {
    parse_scene(doc, "s.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.json_path(), "/materials/a~1b/albedo/0");
  }
}

TEST(SceneLoader, ZeroAreaQuadsAndDegenerateTrianglesAreAccepted) {
  json doc = minimal_scene();
  doc["shapes"] = json::parse(R"([
    {"type": "quad", "corner": [0,0,0], "edge1": [1,0,0], "edge2": [2,0,0], "material": "m"},
    {"type": "mesh", "positions": [0,0,0, 1,1,1, 2,2,2], "indices": [0,1,2, 0,0,0], "material": "m"}])");
  doc["lights"] = json::parse(
      R"([{"type": "quad", "corner": [0,1,0], "edge1": [0,0,0], "edge2": [1,0,0], "radiance": [1,1,1]}])");
  const SceneDescription s = parse_scene(doc, "s.json");
  EXPECT_EQ(std::get<MeshShapeDesc>(s.shapes[1].geometry).triangles.size(), 2u);
  EXPECT_EQ(s.lights.size(), 1u);
}

TEST(MeshLoader, PlyWithQuadIsTriangulated) {
  const SceneDescription s = load_scene(kDataDir / "valid_scene.json");
  const auto& mesh = std::get<MeshShapeDesc>(s.shapes[4].geometry);
  EXPECT_EQ(mesh.positions.size(), 5u);
  ASSERT_EQ(mesh.triangles.size(), 6u);
  EXPECT_EQ(mesh.source, (kDataDir / "meshes/pyramid.ply").string());
  // Transform: uniform scale 0.5, then translate (0.2, 0, -0.5); the apex (0.5, 1, 0.5) lands at:
  bool found_apex = false;
  for (const Vec3d& p : mesh.positions) {
    if (std::abs(p.x - 0.45) < 1e-6 && std::abs(p.y - 0.5) < 1e-6 && std::abs(p.z + 0.25) < 1e-6) {
      found_apex = true;
    }
  }
  EXPECT_TRUE(found_apex);
  for (const auto& t : mesh.triangles) {
    for (uint32_t i : t) EXPECT_LT(i, mesh.positions.size());
  }
}

TEST(MeshLoader, ObjKeepsDegenerateTriangle) {
  const SceneDescription s = load_scene(kDataDir / "valid_scene.json");
  const auto& mesh = std::get<MeshShapeDesc>(s.shapes[5].geometry);
  ASSERT_EQ(mesh.triangles.size(), 3u);
  double total_area = 0;
  int zero_area = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3d& a = mesh.positions[t[0]];
    const double area = 0.5 * length(cross(mesh.positions[t[1]] - a, mesh.positions[t[2]] - a));
    total_area += area;
    zero_area += area == 0;
  }
  EXPECT_DOUBLE_EQ(total_area, 1.0);  // the unit quad
  EXPECT_EQ(zero_area, 1);
}

// scale, then rotate, then translate.
TEST(Transform, TrsOrder) {
  json doc = minimal_scene();
  doc["shapes"] = json::parse(R"([{"type": "mesh", "material": "m",
    "positions": [1,0,0, 0,1,0, 0,0,1], "indices": [0,1,2],
    "transform": {"translate": [1,2,3], "rotate": {"axis": [0,0,2], "angle": 90}, "scale": [2,1,1]}}])");
  const SceneDescription s = parse_scene(doc, "s.json");
  const auto& mesh = std::get<MeshShapeDesc>(s.shapes[0].geometry);
  expect_near(mesh.positions[0], {1, 4, 3});  // (1,0,0) -> (2,0,0) -> (0,2,0) -> (1,4,3)
  expect_near(mesh.positions[1], {0, 2, 3});  // (0,1,0) -> (0,1,0) -> (-1,0,0) -> (0,2,3)
  expect_near(mesh.positions[2], {1, 2, 4});  // (0,0,1) unchanged by scale and rotation
}

TEST(Transform, RotationIsRightHanded) {
  json doc = minimal_scene();
  doc["shapes"] = json::parse(R"([{"type": "mesh", "material": "m",
    "positions": [1,0,0, 0,1,0, 0,0,1], "indices": [0,1,2],
    "transform": {"rotate": {"axis": [0,1,0], "angle": 90}, "scale": 3}}])");
  const SceneDescription s = parse_scene(doc, "s.json");
  const auto& mesh = std::get<MeshShapeDesc>(s.shapes[0].geometry);
  expect_near(mesh.positions[0], {0, 0, -3});  // +X turns toward -Z about +Y
  expect_near(mesh.positions[1], {0, 3, 0});
  expect_near(mesh.positions[2], {3, 0, 0});  // +Z turns toward +X
}

TEST(Transform, MatrixIsRowMajor) {
  const SceneDescription s = load_scene(kDataDir / "valid_scene.json");
  const auto& mesh = std::get<MeshShapeDesc>(s.shapes[6].geometry);
  expect_near(mesh.positions[0], {5, 6, 7});
  expect_near(mesh.positions[1], {6, 6, 7});
  expect_near(mesh.positions[2], {5, 8, 7});
  EXPECT_EQ(mesh.source, "inline mesh at /shapes/6");
}

TEST(ContentHash, IgnoresFormattingButNotContent) {
  TempDir dir;
  const json doc = minimal_scene();
  write_text(dir.path() / "a.json", doc.dump(2));
  write_text(dir.path() / "b.json", doc.dump());
  const std::string ha = load_scene(dir.path() / "a.json").content_hash;
  EXPECT_EQ(ha, load_scene(dir.path() / "b.json").content_hash);
  EXPECT_EQ(ha, parse_scene(doc, dir.path() / "c.json").content_hash);
  json changed = doc;
  changed["render"]["spp"] = 2;
  EXPECT_NE(ha, parse_scene(changed, dir.path() / "c.json").content_hash);
}

TEST(ContentHash, CoversReferencedFiles) {
  TempDir dir;
  json doc = minimal_scene();
  doc["shapes"] = json::parse(R"([{"type": "mesh", "file": "m.obj", "material": "m"}])");
  write_text(dir.path() / "s.json", doc.dump());
  write_text(dir.path() / "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string h1 = load_scene(dir.path() / "s.json").content_hash;
  write_text(dir.path() / "m.obj", "v 0 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_NE(h1, load_scene(dir.path() / "s.json").content_hash);
}

TEST(Environment, LatLongConvention) {
  auto near = [](const Vec3& a, const Vec3& b) {
    return std::abs(a.x - b.x) < 1e-6f && std::abs(a.y - b.y) < 1e-6f &&
           std::abs(a.z - b.z) < 1e-6f;
  };
  EXPECT_TRUE(near(env_latlong_direction(0.3f, 0.f), {0, 1, 0}));  // top row looks up
  EXPECT_TRUE(near(env_latlong_direction(0.f, 0.5f), {0, 0, -1}));
  EXPECT_TRUE(near(env_latlong_direction(0.25f, 0.5f), {1, 0, 0}));
  EXPECT_TRUE(near(env_latlong_direction(0.5f, 0.5f), {0, 0, 1}));
  EXPECT_TRUE(near(env_latlong_direction(0.75f, 0.5f), {-1, 0, 0}));
  for (float u : {0.05f, 0.3f, 0.6f, 0.95f}) {
    for (float v : {0.1f, 0.5f, 0.8f}) {
      const Vec2 uv = env_latlong_uv(env_latlong_direction(u, v));
      EXPECT_NEAR(uv.x, u, 1e-5f);
      EXPECT_NEAR(uv.y, v, 1e-5f);
    }
  }
}

// Writes a width x height image with `channels` channels; value(x, y, c) gives pixels.
template <typename F>
void write_image(const fs::path& p, int width, int height, int channels, F value,
                 OIIO::TypeDesc format = OIIO::TypeDesc::FLOAT) {
  std::vector<float> data(size_t(width * height * channels));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < channels; ++c)
        data[size_t((y * width + x) * channels + c)] = value(x, y, c);
    }
  }
  auto out = OIIO::ImageOutput::create(p.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(p.string(), OIIO::ImageSpec(width, height, channels, format)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, data.data()));
  out->close();
}

json env_scene(const std::string& file) {
  json doc = minimal_scene();
  doc["lights"] = json::array({{{"type", "environment"},
                                {"file", file},
                                {"scale", 2.5},
                                {"rotation", -30},
                                {"group", "sky"}}});
  return doc;
}

TEST(Environment, ReadsExr) {
  TempDir dir;
  write_image(dir.path() / "sky.exr", 8, 4, 4,
              [](int x, int y, int c) { return c == 3 ? 1.f : float(x + 10 * y + 100 * c); });
  write_text(dir.path() / "s.json", env_scene("sky.exr").dump());
  const SceneDescription s = load_scene(dir.path() / "s.json");
  const auto& env = std::get<EnvironmentLightDesc>(s.lights[0].light);
  ASSERT_TRUE(env.image);
  EXPECT_EQ(env.image->width, 8);
  EXPECT_EQ(env.image->height, 4);
  EXPECT_EQ(env.image->pixels[size_t(2 * 8 + 3)], Rgb(23, 123, 223));
  EXPECT_EQ(env.scale, 2.5);
  EXPECT_EQ(env.rotation, -30);
  EXPECT_EQ(env.file, (dir.path() / "sky.exr").string());
  EXPECT_EQ(s.lights[0].group, "sky");
}

TEST(Environment, GreyImageIsReplicated) {
  TempDir dir;
  write_image(dir.path() / "grey.exr", 4, 2, 1, [](int x, int, int) { return float(x); });
  const SceneDescription s = parse_scene(env_scene("grey.exr"), dir.path() / "s.json");
  const auto& env = std::get<EnvironmentLightDesc>(s.lights[0].light);
  EXPECT_EQ(env.image->pixels[3], Rgb(3.f));
}

TEST(Environment, EightBitImageIsLinearized) {
  TempDir dir;
  write_image(
      dir.path() / "sky.png", 2, 1, 3, [](int, int, int) { return 0.5f; }, OIIO::TypeDesc::UINT8);
  const SceneDescription s = parse_scene(env_scene("sky.png"), dir.path() / "s.json");
  const auto& env = std::get<EnvironmentLightDesc>(s.lights[0].light);
  const float expected = std::pow((128.f / 255.f + 0.055f) / 1.055f, 2.4f);  // sRGB decode
  EXPECT_NEAR(env.image->pixels[0].r, expected, 1e-4f);
}

TEST(Environment, RejectsNonFiniteAndNegativePixels) {
  TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  struct Case {
    const char* name;
    float bad;
    const char* expect;
  };
  for (const Case& c : {Case{"nan.exr", nan, "NaN at pixel (3, 1) channel G"},
                        Case{"inf.exr", inf, "Inf at pixel (3, 1) channel G"},
                        Case{"neg.exr", -0.5f, "negative value -0.5"}}) {
    write_image(dir.path() / c.name, 8, 4, 3,
                [&](int x, int y, int ch) { return x == 3 && y == 1 && ch == 1 ? c.bad : 1.f; });
    try {
      parse_scene(env_scene(c.name), dir.path() / "s.json");
      ADD_FAILURE() << c.name << " accepted";
    } catch (const SceneError& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.json_path(), "/lights/0/file");
      EXPECT_NE(what.find(c.expect), std::string::npos) << what;
      EXPECT_NE(what.find(c.name), std::string::npos) << what;
    }
  }
}

// ---- Media ----------------------------------------------------------------

TEST(Media, HomogeneousValuesDefaultsAndBounds) {
  json doc = minimal_scene();
  doc["media"] = json::parse(R"({
    "haze": {"type": "homogeneous", "sigma_s": [0.5, 0.25, 0]},
    "fog": {"type": "homogeneous", "sigma_a": [0.1, 0.2, 0.3], "sigma_s": [1, 2, 3], "g": -0.3,
            "bounds": {"min": [-1, 0, -2], "max": [1, 0.5, 2]}}})");
  const SceneDescription s = parse_scene(doc, "s.json");
  ASSERT_EQ(s.media.size(), 2u);
  // Sorted by name, whatever the order in the file.
  EXPECT_EQ(s.media[0].name, "fog");
  EXPECT_EQ(s.media[1].name, "haze");

  const auto& fog = std::get<HomogeneousMediumDesc>(s.media[0].medium);
  EXPECT_EQ(fog.sigma_a, Rgb(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(fog.sigma_s, Rgb(1.f, 2.f, 3.f));
  EXPECT_EQ(fog.g, -0.3);
  ASSERT_TRUE(fog.bounds.has_value());
  expect_near(fog.bounds->min, {-1, 0, -2});
  expect_near(fog.bounds->max, {1, 0.5, 2});

  const auto& haze = std::get<HomogeneousMediumDesc>(s.media[1].medium);
  EXPECT_EQ(haze.sigma_a, Rgb(0.f));  // default: no absorption
  EXPECT_EQ(haze.sigma_s, Rgb(0.5f, 0.25f, 0.f));
  EXPECT_EQ(haze.g, 0);
  EXPECT_FALSE(haze.bounds.has_value());  // fills the whole scene
}

TEST(Media, EmptyMediaObjectAndExtremeAsymmetry) {
  json doc = minimal_scene();
  doc["media"] = json::object();
  EXPECT_TRUE(parse_scene(doc, "s.json").media.empty());
  doc["media"] = json::parse(R"({"f": {"type": "homogeneous", "sigma_s": [0, 0, 0], "g": 0.999}})");
  EXPECT_EQ(std::get<HomogeneousMediumDesc>(parse_scene(doc, "s.json").media[0].medium).g, 0.999);
  for (double g : {-1.0, 1.0, 1.5}) {
    doc["media"]["f"]["g"] = g;
    try {
      parse_scene(doc, "s.json");
      ADD_FAILURE() << "accepted g = " << g;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.json_path(), "/media/f/g");
    }
  }
}

TEST(Media, MediumNamesAreEscapedInPaths) {
  json doc = minimal_scene();
  doc["media"] = json::parse(R"({"a/b": {"type": "homogeneous", "sigma_s": [1, 1, 1], "g": 2}})");
  try {
    parse_scene(doc, "s.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.json_path(), "/media/a~1b/g");
  }
}

// A small fog volume: a 4x3x2 block of voxels with density 0.5 + i / 8.
DenseVolume test_volume(double voxel_size = 0.25) {
  DenseVolume v;
  v.nx = 4, v.ny = 3, v.nz = 2;
  for (int k = 0; k < v.nz; ++k) {
    for (int j = 0; j < v.ny; ++j) {
      for (int i = 0; i < v.nx; ++i) v.values.push_back(0.5f + float(i) / 8.f);
    }
  }
  v.voxel_size = voxel_size;
  v.origin = {1, 2, 3};
  return v;
}

SceneError expect_scene_error(const fs::path& file) {
  try {
    load_scene(file);
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << file << " was accepted";
  return SceneError("", "", "");
}

TEST(Media, VdbValuesDefaultsAndResolvedPath) {
  TempDir dir;
  fs::create_directories(dir.path() / "vol");
  write_vdb_fog_volume(test_volume(), "density", dir.path() / "vol" / "block.vdb");
  json doc = minimal_scene();
  doc["media"] = json::parse(R"({
    "smoke": {"type": "vdb", "file": "vol/block.vdb"},
    "tuned": {"type": "vdb", "file": "vol/block.vdb", "grid": "density", "density_scale": 2.5,
              "sigma_a": [0.1, 0.2, 0.3], "sigma_s": [4, 5, 6], "g": 0.7,
              "transform": {"translate": [10, 0, 0], "scale": 2},
              "emission_grid": "density", "emission_scale": 3, "emission_color": [1, 0.5, 0.25]}})");
  write_text(dir.path() / "s.json", doc.dump());
  const SceneDescription s = load_scene(dir.path() / "s.json");
  ASSERT_EQ(s.media.size(), 2u);

  const auto& smoke = std::get<VdbMediumDesc>(s.media[0].medium);
  EXPECT_EQ(s.media[0].name, "smoke");
  EXPECT_EQ(fs::path(smoke.file), dir.path() / "vol" / "block.vdb");
  EXPECT_EQ(smoke.grid, "density");
  ASSERT_NE(smoke.density, nullptr);
  EXPECT_NEAR(smoke.density->voxel(3, 0, 0), 0.875f, 1e-6f);
  EXPECT_NEAR(smoke.density->max_value(), 0.875f, 1e-6f);
  EXPECT_EQ(smoke.density_scale, 1);
  EXPECT_EQ(smoke.sigma_a, Rgb(0.f));
  EXPECT_EQ(smoke.sigma_s, Rgb(1.f));
  EXPECT_EQ(smoke.g, 0);
  expect_near(smoke.transform.apply_point({1, 2, 3}), {1, 2, 3});  // identity
  EXPECT_TRUE(smoke.emission_grid.empty());
  EXPECT_EQ(smoke.emission, nullptr);
  EXPECT_EQ(smoke.emission_scale, 0);
  EXPECT_EQ(smoke.emission_color, Rgb(1.f));

  const auto& tuned = std::get<VdbMediumDesc>(s.media[1].medium);
  EXPECT_EQ(tuned.density_scale, 2.5);
  EXPECT_EQ(tuned.sigma_a, Rgb(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(tuned.sigma_s, Rgb(4.f, 5.f, 6.f));
  EXPECT_EQ(tuned.g, 0.7);
  ASSERT_NE(tuned.emission, nullptr);
  EXPECT_EQ(tuned.emission_grid, "density");
  EXPECT_EQ(tuned.emission_scale, 3);
  EXPECT_EQ(tuned.emission_color, Rgb(1.f, 0.5f, 0.25f));
  // The grid's own index->world map first (voxel 0.25, origin (1,2,3)), then `transform`.
  const Vec3d grid_world = tuned.density->index_to_world().apply_point({2, 0, 0});
  expect_near(grid_world, {1.5, 2, 3}, 1e-9);
  expect_near(tuned.transform.apply_point(grid_world), {13, 4, 6}, 1e-9);
}

TEST(Media, VdbEmissionScaleZeroWithGridIsAllowed) {
  TempDir dir;
  write_vdb_fog_volume(test_volume(), "density", dir.path() / "b.vdb");
  json doc = minimal_scene();
  doc["media"] =
      json::parse(R"({"s": {"type": "vdb", "file": "b.vdb", "emission_grid": "density"}})");
  write_text(dir.path() / "s.json", doc.dump());
  const auto& m = std::get<VdbMediumDesc>(load_scene(dir.path() / "s.json").media[0].medium);
  EXPECT_NE(m.emission, nullptr);
  EXPECT_EQ(m.emission_scale, 0);
}

TEST(Media, VdbMissingGridListsTheGridsOfTheFile) {
  TempDir dir;
  write_vdb_fog_volume(test_volume(), "density", dir.path() / "b.vdb");
  json doc = minimal_scene();
  doc["media"] =
      json::parse(R"({"smoke": {"type": "vdb", "file": "b.vdb", "grid": "temperature"}})");
  write_text(dir.path() / "s.json", doc.dump());
  SceneError e = expect_scene_error(dir.path() / "s.json");
  EXPECT_EQ(e.file(), (dir.path() / "s.json").string());
  EXPECT_EQ(e.json_path(), "/media/smoke/grid");
  EXPECT_NE(e.message().find("temperature"), std::string::npos) << e.what();
  EXPECT_NE(e.message().find("density"), std::string::npos) << "grids not listed: " << e.what();

  // The default grid name is "density": a file without it fails at /grid too.
  write_vdb_fog_volume(test_volume(), "smoke", dir.path() / "b.vdb");
  doc["media"]["smoke"].erase("grid");
  write_text(dir.path() / "s.json", doc.dump());
  e = expect_scene_error(dir.path() / "s.json");
  EXPECT_EQ(e.json_path(), "/media/smoke/grid");
  EXPECT_NE(e.message().find("smoke"), std::string::npos) << "grids not listed: " << e.what();

  // A missing emission grid is reported at /emission_grid.
  write_vdb_fog_volume(test_volume(), "density", dir.path() / "b.vdb");
  doc["media"]["smoke"]["emission_grid"] = "temperature";
  write_text(dir.path() / "s.json", doc.dump());
  e = expect_scene_error(dir.path() / "s.json");
  EXPECT_EQ(e.json_path(), "/media/smoke/emission_grid");
  EXPECT_NE(e.message().find("density"), std::string::npos) << "grids not listed: " << e.what();
}

TEST(Media, VdbMissingOrUnreadableFile) {
  TempDir dir;
  json doc = minimal_scene();
  doc["media"] = json::parse(R"({"smoke": {"type": "vdb", "file": "sub/none.vdb"}})");
  write_text(dir.path() / "s.json", doc.dump());
  SceneError e = expect_scene_error(dir.path() / "s.json");
  EXPECT_EQ(e.json_path(), "/media/smoke/file");
  EXPECT_EQ(e.message(), "VDB file not found: '" + (dir.path() / "sub/none.vdb").string() + "'");

  fs::create_directories(dir.path() / "sub");
  write_text(dir.path() / "sub/none.vdb", "this is not an OpenVDB file\n");
  e = expect_scene_error(dir.path() / "s.json");
  EXPECT_EQ(e.json_path(), "/media/smoke/file");
  EXPECT_NE(e.message().find("none.vdb"), std::string::npos) << e.what();
}

TEST(Media, CheapValuesAreValidatedBeforeTheFileIsRead) {
  json doc = minimal_scene();
  doc["media"] =
      json::parse(R"({"smoke": {"type": "vdb", "file": "absent.vdb", "sigma_s": [1, -1, 1]}})");
  try {
    parse_scene(doc, "s.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.json_path(), "/media/smoke/sigma_s/1");
  }
}

TEST(ContentHash, CoversVdbFiles) {
  TempDir dir;
  write_vdb_fog_volume(test_volume(), "density", dir.path() / "b.vdb");
  json doc = minimal_scene();
  doc["media"] = json::parse(R"({"smoke": {"type": "vdb", "file": "b.vdb"}})");
  write_text(dir.path() / "s.json", doc.dump());
  const std::string h1 = load_scene(dir.path() / "s.json").content_hash;
  EXPECT_EQ(h1, load_scene(dir.path() / "s.json").content_hash);
  DenseVolume v = test_volume();
  v.values[5] = 2.f;
  write_vdb_fog_volume(v, "density", dir.path() / "b.vdb");
  EXPECT_NE(h1, load_scene(dir.path() / "s.json").content_hash);
}

// The shared production smoke (Houdini export, one float grid "density").
TEST(Media, LoadsTheSharedSmokeVdb) {
  const fs::path smoke = fs::path(VESPER_SOURCE_DIR) / ".." / "shared" / "data" / "smoke.vdb";
  if (!fs::exists(smoke)) GTEST_SKIP() << "no " << smoke;
  json doc = minimal_scene();
  doc["media"]["smoke"] = {{"type", "vdb"},
                           {"file", fs::absolute(smoke).lexically_normal().string()},
                           {"density_scale", 2},
                           {"transform", {{"scale", 0.01}}}};
  const SceneDescription s = parse_scene(doc, "/nowhere/s.json");  // absolute file: base dir unused
  const auto& m = std::get<VdbMediumDesc>(s.media[0].medium);
  ASSERT_NE(m.density, nullptr);
  EXPECT_EQ(m.density->name(), "density");
  EXPECT_GT(m.density->max_value(), 1.f);  // vdb_print: max 5.71
  EXPECT_FALSE(m.density->active_box().empty());
  EXPECT_EQ(m.density_scale, 2);
}

// ---- Layers and AOVs ---------------------------------------------------------

TEST(Aovs, AllTenNamesInRequestOrder) {
  json doc = minimal_scene();
  doc["render"]["aovs"] = json::parse(R"(["volume_indirect", "emission", "albedo", "diffuse_direct",
    "normal", "diffuse_indirect", "specular_direct", "depth", "specular_indirect", "volume_direct"])");
  EXPECT_EQ(parse_scene(doc, "s.json").render.aovs,
            (std::vector<Aov>{Aov::VolumeIndirect, Aov::Emission, Aov::Albedo, Aov::DiffuseDirect,
                              Aov::Normal, Aov::DiffuseIndirect, Aov::SpecularDirect, Aov::Depth,
                              Aov::SpecularIndirect, Aov::VolumeDirect}));
}

// Lights in groups "window" and "candles" plus one without a group, and a fog.
json layered_scene() {
  json doc = minimal_scene();
  doc["lights"] = json::parse(R"([
    {"type": "quad", "corner": [0, 2, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "radiance": [5, 5, 5], "group": "window"},
    {"type": "point", "position": [1, 1, 0], "intensity": [1, 1, 1], "group": "candles"},
    {"type": "point", "position": [-1, 1, 0], "intensity": [1, 1, 1], "group": "candles"},
    {"type": "point", "position": [0, 1, 1], "intensity": [1, 1, 1]}])");
  doc["media"] = json::parse(R"({"fog": {"type": "homogeneous", "sigma_s": [0.1, 0.1, 0.1]}})");
  return doc;
}

SceneError expect_parse_error(const json& doc) {
  try {
    parse_scene(doc, "s.json");
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted " << doc.dump();
  return SceneError("", "", "");
}

TEST(Layers, NoneByDefault) {
  EXPECT_TRUE(parse_scene(minimal_scene(), "s.json").layers.empty());
  json doc = minimal_scene();
  doc["layers"] = json::object();
  EXPECT_TRUE(parse_scene(doc, "s.json").layers.empty());
}

TEST(Layers, SelectionsDefaultsAndOrder) {
  json doc = layered_scene();
  doc["layers"] = json::parse(R"({
    "surfaces": {"paths": "surface"},
    "fog": {"paths": "volume"},
    "lightrays": {"paths": "volume", "lights": ["window"]},
    "everything": {},
    "rest": {"paths": "all", "lights": ["default", "emission", "candles"]}})");
  const SceneDescription s = parse_scene(doc, "s.json");
  ASSERT_EQ(s.layers.size(), 5u);
  // Sorted by name, whatever the order in the file.
  const std::vector<std::string> names = {"everything", "fog", "lightrays", "rest", "surfaces"};
  for (size_t i = 0; i < names.size(); ++i) EXPECT_EQ(s.layers[i].name, names[i]);
  for (const LayerDesc& l : s.layers) EXPECT_FALSE(l.variant.has_value()) << l.name;

  EXPECT_EQ(s.layers[0].paths, PathSelection::All);  // default
  EXPECT_FALSE(s.layers[0].lights.has_value());      // default: every group
  EXPECT_EQ(s.layers[1].paths, PathSelection::Volume);
  EXPECT_FALSE(s.layers[1].lights.has_value());
  EXPECT_EQ(s.layers[2].paths, PathSelection::Volume);
  EXPECT_EQ(s.layers[2].lights, (std::vector<std::string>{"window"}));
  EXPECT_EQ(s.layers[3].paths, PathSelection::All);
  EXPECT_EQ(s.layers[3].lights, (std::vector<std::string>{"default", "emission", "candles"}));
  EXPECT_EQ(s.layers[4].paths, PathSelection::Surface);
}

TEST(Layers, EmissionGroupIsAlwaysKnownDefaultOnlyWithUngroupedLights) {
  json doc = minimal_scene();  // no lights, no media
  doc["layers"] = json::parse(R"({"glow": {"lights": ["emission"]}})");
  EXPECT_EQ(parse_scene(doc, "s.json").layers[0].lights, (std::vector<std::string>{"emission"}));

  doc["layers"]["glow"]["lights"] = {"default"};
  SceneError e = expect_parse_error(doc);
  EXPECT_EQ(e.json_path(), "/layers/glow/lights/0");
  EXPECT_NE(e.message().find("known groups: emission)"), std::string::npos) << e.what();

  doc["lights"] =
      json::parse(R"([{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]}])");
  EXPECT_EQ(parse_scene(doc, "s.json").layers[0].lights, (std::vector<std::string>{"default"}));

  doc["lights"][0]["group"] = "lamp";
  e = expect_parse_error(doc);
  EXPECT_EQ(e.message(),
            "unknown light group \"default\" (known groups: lamp, emission); \"default\" is the "
            "group of the lights without a 'group', and every light has one");
}

TEST(Layers, VariantEveryField) {
  TempDir dir;
  write_vdb_fog_volume(test_volume(), "density", dir.path() / "b.vdb");
  json doc = layered_scene();
  doc["media"]["smoke"] = {{"type", "vdb"}, {"file", "b.vdb"}};
  doc["layers"] = json::parse(R"({
    "rays_dense": {"variant": {"media": {"smoke": {"density_scale": 4}}, "lights": ["window"]},
                   "paths": "volume"},
    "tuned": {"variant": {"media": {
                "smoke": {"density_scale": 0, "sigma_a": [0.1, 0.2, 0.3], "sigma_s": [1, 2, 3],
                          "g": -0.5, "enabled": true},
                "fog": {"enabled": false, "g": 0.9}}},
              "lights": ["window", "emission"]},
    "dark": {"variant": {"lights": []}, "paths": "surface"},
    "no_fog": {"variant": {"media": {"fog": {"sigma_s": [0, 0, 0]}}},
               "lights": ["candles"]}})");
  write_text(dir.path() / "s.json", doc.dump());
  const SceneDescription s = load_scene(dir.path() / "s.json");
  ASSERT_EQ(s.layers.size(), 4u);

  const LayerDesc& dark = s.layers[0];
  EXPECT_EQ(dark.name, "dark");
  EXPECT_EQ(dark.paths, PathSelection::Surface);
  ASSERT_TRUE(dark.variant.has_value());
  EXPECT_TRUE(dark.variant->media.empty());
  EXPECT_EQ(dark.variant->lights, std::vector<std::string>{});  // no lights at all

  const LayerDesc& no_fog = s.layers[1];
  EXPECT_EQ(no_fog.name, "no_fog");
  EXPECT_EQ(no_fog.lights, (std::vector<std::string>{"candles"}));
  ASSERT_TRUE(no_fog.variant.has_value());
  EXPECT_FALSE(no_fog.variant->lights.has_value());  // every light
  ASSERT_EQ(no_fog.variant->media.size(), 1u);
  const MediumOverride& thin = no_fog.variant->media.at("fog");
  EXPECT_EQ(thin.sigma_s, Rgb(0.f));
  EXPECT_FALSE(thin.sigma_a || thin.density_scale || thin.g || thin.enabled);

  const LayerDesc& dense = s.layers[2];
  EXPECT_EQ(dense.name, "rays_dense");
  EXPECT_EQ(dense.paths, PathSelection::Volume);
  EXPECT_FALSE(dense.lights.has_value());
  ASSERT_TRUE(dense.variant.has_value());
  EXPECT_EQ(dense.variant->lights, (std::vector<std::string>{"window"}));
  ASSERT_EQ(dense.variant->media.size(), 1u);
  EXPECT_EQ(dense.variant->media.at("smoke").density_scale, 4.0);

  const LayerDesc& tuned = s.layers[3];
  EXPECT_EQ(tuned.name, "tuned");
  EXPECT_EQ(tuned.paths, PathSelection::All);
  EXPECT_EQ(tuned.lights, (std::vector<std::string>{"window", "emission"}));
  ASSERT_TRUE(tuned.variant.has_value());
  EXPECT_FALSE(tuned.variant->lights.has_value());
  ASSERT_EQ(tuned.variant->media.size(), 2u);
  const MediumOverride& smoke = tuned.variant->media.at("smoke");
  EXPECT_EQ(smoke.density_scale, 0.0);
  EXPECT_EQ(smoke.sigma_a, Rgb(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(smoke.sigma_s, Rgb(1.f, 2.f, 3.f));
  EXPECT_EQ(smoke.g, -0.5);
  EXPECT_EQ(smoke.enabled, true);
  const MediumOverride& fog = tuned.variant->media.at("fog");
  EXPECT_EQ(fog.enabled, false);
  EXPECT_EQ(fog.g, 0.9);
  EXPECT_FALSE(fog.density_scale || fog.sigma_a || fog.sigma_s);
}

TEST(Layers, OverrideValuesAreRangeChecked) {
  struct Case {
    const char* override_json;
    const char* path;
    const char* message;
  };
  const Case cases[] = {
      {R"({"sigma_a": [0, -1, 0]})", "/layers/x/variant/media/fog/sigma_a/1",
       "expected a non-negative number, got -1"},
      {R"({"sigma_s": [1, 1]})", "/layers/x/variant/media/fog/sigma_s",
       "expected an RGB array of 3 numbers"},
      {R"({"g": 1})", "/layers/x/variant/media/fog/g", "expected a number in (-1, 1), got 1"},
      {R"({"enabled": 0})", "/layers/x/variant/media/fog/enabled", "expected true or false, got 0"},
      {R"({"sigma": [1, 1, 1]})", "/layers/x/variant/media/fog/sigma",
       "unknown key 'sigma' (expected one of: density_scale, sigma_a, sigma_s, g, enabled)"},
  };
  for (const Case& c : cases) {
    json doc = layered_scene();
    doc["layers"]["x"]["variant"]["media"]["fog"] = json::parse(c.override_json);
    const SceneError e = expect_parse_error(doc);
    EXPECT_EQ(e.json_path(), c.path) << c.override_json;
    EXPECT_NE(e.message().find(c.message), std::string::npos) << e.what();
  }
}

TEST(Layers, NegativeDensityScaleOverrideOnVdbIsRejected) {
  TempDir dir;
  write_vdb_fog_volume(test_volume(), "density", dir.path() / "b.vdb");
  json doc = minimal_scene();
  doc["media"]["smoke"] = {{"type", "vdb"}, {"file", "b.vdb"}};
  doc["layers"] = json::parse(R"({"x": {"variant": {"media": {"smoke": {"density_scale": -1}}}}})");
  write_text(dir.path() / "s.json", doc.dump());
  const SceneError e = expect_scene_error(dir.path() / "s.json");
  EXPECT_EQ(e.json_path(), "/layers/x/variant/media/smoke/density_scale");
  EXPECT_EQ(e.message(), "expected a non-negative number, got -1");
}

TEST(Layers, VariantInASceneWithoutMedia) {
  json doc = minimal_scene();
  doc["layers"] = json::parse(R"({"x": {"variant": {"media": {"fog": {"enabled": false}}}}})");
  const SceneError e = expect_parse_error(doc);
  EXPECT_EQ(e.json_path(), "/layers/x/variant/media/fog");
  EXPECT_EQ(e.message(), "unknown medium \"fog\" (the scene has no media)");
}

TEST(Layers, LayerNames) {
  for (const char* good : {"fog", "Fog-2", "light_rays", "A", "0", "Albedo", "beauty2", "-"}) {
    json doc = minimal_scene();
    doc["layers"][good] = json::object();
    EXPECT_EQ(parse_scene(doc, "s.json").layers.at(0).name, good);
  }
  struct Bad {
    const char* name;
    const char* path;
    const char* message;
  };
  const Bad bad[] = {
      {"", "/layers/", "expected a non-empty layer name"},
      {"fog.dense", "/layers/fog.dense", "letters, digits, '_' and '-'"},
      {"fog dense", "/layers/fog dense", "letters, digits, '_' and '-'"},
      {"a/b", "/layers/a~1b", "got \"a/b\""},
      {"fög", "/layers/fög", "letters, digits, '_' and '-'"},
      {"beauty", "/layers/beauty", "got \"beauty\""},
      {"normal", "/layers/normal", "other than the names of the beauty and the standard AOVs"},
      {"volume_indirect", "/layers/volume_indirect", "got \"volume_indirect\""},
      {"emission", "/layers/emission", "got \"emission\""},
  };
  for (const Bad& b : bad) {
    json doc = minimal_scene();
    doc["layers"][b.name] = json::object();
    const SceneError e = expect_parse_error(doc);
    EXPECT_EQ(e.json_path(), b.path) << b.name;
    EXPECT_NE(e.message().find(b.message), std::string::npos) << e.what();
  }
}

TEST(Layers, LayerMustBeAnObjectAndLightsStrings) {
  json doc = layered_scene();
  doc["layers"]["fog"] = "volume";
  SceneError e = expect_parse_error(doc);
  EXPECT_EQ(e.json_path(), "/layers/fog");
  EXPECT_EQ(e.message(), "expected an object, got string \"volume\"");

  doc["layers"]["fog"] = json::parse(R"({"lights": "window"})");
  e = expect_parse_error(doc);
  EXPECT_EQ(e.json_path(), "/layers/fog/lights");
  EXPECT_EQ(e.message(), "expected a non-empty array of light group names, got string \"window\"");

  doc["layers"]["fog"] = json::parse(R"({"lights": ["window", 3]})");
  e = expect_parse_error(doc);
  EXPECT_EQ(e.json_path(), "/layers/fog/lights/1");
  EXPECT_EQ(e.message(), "expected a string, got 3");

  doc["layers"]["fog"] = json::parse(R"({"variant": {"lights": ["window", "sun"]}})");
  e = expect_parse_error(doc);
  EXPECT_EQ(e.json_path(), "/layers/fog/variant/lights/1");
  EXPECT_EQ(e.message(),
            "unknown light group \"sun\" (known groups: candles, window, default, emission)");

  doc["layers"]["fog"] = json::parse(R"({"variant": {"lights": ["window", "window"]}})");
  e = expect_parse_error(doc);
  EXPECT_EQ(e.json_path(), "/layers/fog/variant/lights/1");
}

TEST(Layers, ContentHashCoversLayers) {
  json doc = layered_scene();
  const std::string h0 = parse_scene(doc, "s.json").content_hash;
  doc["layers"]["fog"]["paths"] = "volume";
  const std::string h1 = parse_scene(doc, "s.json").content_hash;
  doc["layers"]["fog"]["paths"] = "surface";
  EXPECT_NE(h0, h1);
  EXPECT_NE(h1, parse_scene(doc, "s.json").content_hash);
}

}  // namespace
}  // namespace vesper
