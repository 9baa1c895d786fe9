// render.clamp, the indirect sample clamp: off is the exact estimator bit for
// bit; on, no sample's indirect light exceeds it (so no pixel of an indirect
// AOV does), direct light is untouched, and the image says it is clamped.
#include <gtest/gtest.h>

#include <algorithm>

#include "renderer/render/render.h"
#include "renderer/scene/scene.h"
#include "scene_fixtures.h"

namespace vesper::test {
namespace {

// The small Cornell box lit by a tiny, very bright ceiling light: BSDF
// samples that hit it after a bounce, and caustics off the metal sphere, are
// the fireflies.
SceneDescription firefly_box() {
  SceneDescription d = small_cornell(24, 24, 16);
  d.lights.clear();
  add_light(d, QuadLightDesc{{-0.03, 1.98, -0.03}, {0.06, 0, 0}, {0, 0, 0.06}, Rgb(1200.f)});
  d.render.aovs = {Aov::DiffuseDirect, Aov::DiffuseIndirect, Aov::SpecularDirect,
                   Aov::SpecularIndirect};
  return d;
}

RenderResult render_with(const Scene& scene, std::optional<double> clamp, int threads = 0) {
  RenderOptions o;
  o.clamp = clamp;
  o.threads = threads;
  return render(scene, o);
}

float max_of(const LayeredImage& img, const std::string& layer) {
  float m = 0.f;
  for (const char* c : {".R", ".G", ".B"}) {
    const int i = img.channel_index(layer + c);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) m = std::max(m, img.at(x, y, size_t(i)));
  }
  return m;
}

double mean_rgb(const LayeredImage& img) {
  double s = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (size_t c = 0; c < 3; ++c) s += img.at(x, y, c);
  return s / (3.0 * img.width * img.height);
}

TEST(IndirectClamp, AClampNoSampleReachesLeavesTheImageBitwiseAsWithout) {
  const Scene scene = build_scene(firefly_box());
  const RenderResult off = render_with(scene, std::nullopt);
  const RenderResult huge = render_with(scene, 1e30);
  EXPECT_EQ(off.image.pixels, huge.image.pixels);
  EXPECT_EQ(off.image.metadata.count("vesper:clamp"), 0u);
  EXPECT_EQ(huge.image.metadata.at("vesper:clamp"), "1e+30");
}

TEST(IndirectClamp, NoIndirectSampleAboveTheClampAndDirectLightUntouched) {
  const Scene scene = build_scene(firefly_box());
  const float clamp = 0.25f;
  const RenderResult off = render_with(scene, std::nullopt);
  const RenderResult on = render_with(scene, clamp);
  // The scene has fireflies above the clamp without it...
  EXPECT_GT(std::max(max_of(off.image, "diffuse_indirect"), max_of(off.image, "specular_indirect")),
            4 * clamp);
  // ...and no pixel (a mean of samples) of an indirect AOV above it with it.
  EXPECT_LE(max_of(on.image, "diffuse_indirect"), clamp * (1 + 1e-6f));
  EXPECT_LE(max_of(on.image, "specular_indirect"), clamp * (1 + 1e-6f));
  EXPECT_LT(mean_rgb(on.image), mean_rgb(off.image));
  for (const char* direct : {"diffuse_direct.R", "specular_direct.G"}) {
    const int i = on.image.channel_index(direct);
    for (int y = 0; y < on.image.height; ++y)
      for (int x = 0; x < on.image.width; ++x)
        ASSERT_EQ(on.image.at(x, y, size_t(i)), off.image.at(x, y, size_t(i))) << direct;
  }
  EXPECT_EQ(on.image.metadata.at("vesper:clamp"), "0.25");
  std::printf("mean RGB: unclamped %.5f, clamp 0.25 %.5f\n", mean_rgb(off.image),
              mean_rgb(on.image));
}

TEST(IndirectClamp, SameImageForAnyThreadCount) {
  const Scene scene = build_scene(firefly_box());
  EXPECT_EQ(render_with(scene, 0.5, 1).image.pixels, render_with(scene, 0.5, 2).image.pixels);
}

TEST(IndirectClamp, ANonPositiveClampIsAnErrorNamingTheSetting) {
  const Scene scene = build_scene(firefly_box());
  try {
    render_with(scene, -1.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("render.clamp (--clamp)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesper::test
