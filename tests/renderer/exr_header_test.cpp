// What the EXR header says and how compositors read it: typed vesper:*
// attributes, the camera as worldToCamera / worldToNDC, the channel order.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "renderer/output/exr_io.h"
#include "renderer/output/metadata_keys.h"
#include "renderer/output/metadata_text.h"
#include "renderer/render/frame.h"
#include "renderer/scene/camera_matrices.h"
#include "renderer/scene/scene_loader.h"
#include "tests/common/temp_dir.h"
#include "tests/renderer/minimal_scene.h"

namespace fs = std::filesystem;

namespace vesper::test {
namespace {

namespace key = metadata_key;

OIIO::ImageSpec header(const fs::path& file) {
  auto in = OIIO::ImageInput::open(file.string());
  return in->spec();
}

LayeredImage tiny_image() {
  LayeredImage img;
  img.width = img.height = 2;
  img.channels = {"R", "G", "B"};
  img.pixels.assign(12, 0.5f);
  return img;
}

TEST(ExrHeader, NumbersAreTypedAttributesAndReadBackAsTheSameText) {
  const TempDir dir("exr");
  LayeredImage img = tiny_image();
  img.metadata = {{key::kSpp, "16"},
                  {key::kFrame, "7"},
                  {key::kRenderSeconds, "0.123456789"},
                  {key::kNoiseReached, "1e-07"},
                  {key::kSeed, "18446744073709551615"},
                  {key::kNonfiniteSamples, "5000000000"},  // beyond int: stays text
                  {key::kSceneHash, "2a831a5e4ae55db2"},
                  {key::kWorldToCamera, "1 0 0 0 0 1 0 0 0 0 1 0 -0.5 2 -3.25 1"}};
  write_exr(img, dir / "m.exr");
  const OIIO::ImageSpec spec = header(dir / "m.exr");
  auto type = [&](const char* k) { return spec.getattributetype(k); };
  EXPECT_EQ(type(key::kSpp), OIIO::TypeInt);
  EXPECT_EQ(type(key::kFrame), OIIO::TypeInt);
  EXPECT_EQ(type(key::kRenderSeconds), OIIO::TypeDesc::DOUBLE);
  EXPECT_EQ(type(key::kNoiseReached), OIIO::TypeDesc::DOUBLE);
  EXPECT_EQ(type(key::kSeed), OIIO::TypeString);
  EXPECT_EQ(type(key::kNonfiniteSamples), OIIO::TypeString);
  EXPECT_EQ(type(key::kSceneHash), OIIO::TypeString);
  EXPECT_EQ(type(key::kWorldToCamera), OIIO::TypeMatrix44);
  EXPECT_EQ(spec.get_int_attribute(key::kSpp), 16);

  // read_exr keeps only vesper:* keys; each is the text it was written with.
  std::map<std::string, std::string> want = img.metadata;
  want.erase(key::kWorldToCamera);
  EXPECT_EQ(read_exr(dir / "m.exr").metadata, want);
  EXPECT_EQ(read_exr_metadata(dir / "m.exr"), want);
}

TEST(ExrHeader, ANonNumberForANumericKeyIsRefused) {
  const TempDir dir("exr");
  LayeredImage img = tiny_image();
  img.metadata[key::kSpp] = "sixteen";
  try {
    write_exr(img, dir / "m.exr");
    FAIL() << "expected an ImageIoError";
  } catch (const ImageIoError& e) {
    EXPECT_NE(std::string(e.what()).find("'vesper:spp': expected an integer, got 'sixteen'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

// A small sphere, off-centre, seen by a tilted camera far from the origin on
// a wide film; the camera moves over frames, the image is of frame 2.
SceneDescription sphere_scene(Vec3d& centre) {
  nlohmann::json doc = minimal_scene();
  doc["film"] = {{"width", 96}, {"height", 64}};
  doc["render"] = {{"spp", 16}, {"aovs", {"albedo"}}};
  doc["camera"] = nlohmann::json::parse(R"({"type": "perspective",
      "from": {"keys": [[1, [1000, 480, 2030]], [3, [1000, 520, 1990]]]},
      "to": [1002, 501, 2000], "up": [0.1, 1, 0], "fov": 35})");
  centre = {1003.1, 502.2, 2001.3};
  doc["shapes"] = {{{"type", "sphere"},
                    {"center", {centre.x, centre.y, centre.z}},
                    {"radius", 0.15},
                    {"material", "m"}}};
  return parse_scene(doc, "sphere.json", SceneLoadOptions{.frame = 2});
}

std::array<float, 16> matrix_attribute(const fs::path& file, const char* name) {
  const OIIO::ImageSpec spec = header(file);
  const OIIO::ParamValue* p = spec.find_attribute(name);
  EXPECT_TRUE(p && p->type() == OIIO::TypeMatrix44) << name;
  std::array<float, 16> m{};
  if (p) std::copy_n(static_cast<const float*>(p->data()), 16, m.begin());
  return m;
}

TEST(ExrHeader, WorldToNdcProjectsASphereOntoThePixelsWhereItRenders) {
  const TempDir dir("exr");
  Vec3d c;
  const SceneDescription desc = sphere_scene(c);
  const LayeredImage img = render_frame(desc).image;
  write_exr(img, dir / "s.exr");

  // Where it renders: the coverage-weighted centroid of albedo.R, in raster units.
  const int a = img.channel_index("albedo.R");
  double sw = 0, sx = 0, sy = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double w = img.at(x, y, size_t(a));
      sw += w, sx += w * (x + 0.5), sy += w * (y + 0.5);
    }
  ASSERT_GT(sw, 4.0) << "the sphere is in view";

  // Where the header says: p * worldToNDC, divided by w; NDC [-1, 1] with y up.
  const std::array<float, 16> m = matrix_attribute(dir / "s.exr", "worldToNDC");
  const double p[4] = {c.x, c.y, c.z, 1};
  double q[4] = {};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) q[j] += p[i] * double(m[size_t(i * 4 + j)]);
  ASSERT_GT(q[3], 0) << "in front of the camera";
  const double px = (q[0] / q[3] + 1) / 2 * img.width, py = (1 - q[1] / q[3]) / 2 * img.height;
  // The centroid of a sphere's image lies within r²/d² of its centre's
  // projection (far below a pixel here); the rest is the 16-sample estimate.
  EXPECT_NEAR(sx / sw, px, 0.25);
  EXPECT_NEAR(sy / sw, py, 0.25);
  EXPECT_GT(std::fabs(px - img.width / 2.0), 5) << "the test must see an off-centre sphere";

  // worldToCamera: the camera at the origin, the sphere in front (-Z), at its distance.
  const std::array<float, 16> v = matrix_attribute(dir / "s.exr", "worldToCamera");
  double cam[4] = {};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) cam[j] += p[i] * double(v[size_t(i * 4 + j)]);
  EXPECT_DOUBLE_EQ(cam[3], 1);
  EXPECT_LT(cam[2], 0);
  EXPECT_NEAR(std::hypot(cam[0], cam[1], cam[2]), length(c - desc.camera.from), 1e-3);
}

TEST(ExrHeader, AnAnimatedCameraWritesTheFramesMatrices) {
  Vec3d c;
  const SceneDescription f2 = sphere_scene(c);
  EXPECT_DOUBLE_EQ(f2.camera.from.y, 500);  // halfway between the keys
  const LayeredImage img = render_frame(f2).image;
  const CameraMatrices m = camera_matrices(f2.camera, f2.film);
  EXPECT_EQ(img.metadata.at(key::kWorldToCamera), metadata_matrix(m.world_to_camera));
  EXPECT_EQ(img.metadata.at(key::kWorldToNdc), metadata_matrix(m.world_to_ndc));
  CameraDesc first = f2.camera;
  first.from = {1000, 480, 2030};
  EXPECT_NE(metadata_matrix(camera_matrices(first, f2.film).world_to_camera),
            img.metadata.at(key::kWorldToCamera));
}

// docs/scene-format.md, "Channel order": OpenEXR keeps channels sorted by
// name; readers list the unlayered ones first (R, G, B, A, then the rest by
// name), then each layer by name with its R, G, B, A first, then the rest.
TEST(ExrHeader, ChannelsReadBackInTheDocumentedOrder) {
  const TempDir dir("exr");
  nlohmann::json doc = minimal_scene();
  doc["render"] = {{"spp", 2}, {"aovs", {"variance", "normal", "emission", "depth", "albedo"}}};
  doc["layers"] = {{"zfog", {{"paths", "surface"}}}, {"back", {{"paths", "all"}}}};
  RenderOptions options;
  options.layer_variance = true;
  const LayeredImage img = render_frame(parse_scene(doc, "order.json"), options).image;
  write_exr(img, dir / "o.exr");
  EXPECT_EQ(read_exr(dir / "o.exr").channels, (std::vector<std::string>{"R",
                                                                        "G",
                                                                        "B",
                                                                        "A",  //
                                                                        "albedo.R",
                                                                        "albedo.G",
                                                                        "albedo.B",  //
                                                                        "albedo.variance.R",
                                                                        "albedo.variance.G",
                                                                        "albedo.variance.B",  //
                                                                        "back.R",
                                                                        "back.G",
                                                                        "back.B",  //
                                                                        "back.variance.R",
                                                                        "back.variance.G",
                                                                        "back.variance.B",  //
                                                                        "depth.Z",          //
                                                                        "emission.R",
                                                                        "emission.G",
                                                                        "emission.B",  //
                                                                        "emission.variance.R",
                                                                        "emission.variance.G",
                                                                        "emission.variance.B",  //
                                                                        "normal.X",
                                                                        "normal.Y",
                                                                        "normal.Z",  //
                                                                        "variance.R",
                                                                        "variance.G",
                                                                        "variance.B",  //
                                                                        "zfog.R",
                                                                        "zfog.G",
                                                                        "zfog.B",  //
                                                                        "zfog.variance.R",
                                                                        "zfog.variance.G",
                                                                        "zfog.variance.B"}));
}

}  // namespace
}  // namespace vesper::test
