// Light tracing (light_tracer.h): the light tracer and the camera paths
// split path space between them, so with it the image keeps its expected
// value; its splats keep the render deterministic and its sample ranges
// mergeable; and it runs only where it paid off.
#include <gtest/gtest.h>

#include <algorithm>

#include "estimator_agreement.h"
#include "range_merge.h"
#include "renderer/integrator/light_tracer.h"
#include "scene_fixtures.h"

namespace vesper::test {
namespace {

// A spot light's shaft onto a diffuse floor in fog, an occluder in it, a
// metal wall (a first event there stays with the camera paths) and a dim
// point light: most of the image is lit after two or more events.
SceneDescription fog_pool_scene(FilterType filter, int max_depth = 6, double fov = 50) {
  SceneDescription d = empty_scene(24, 24, 48, max_depth);
  d.film.filter = filter;
  d.camera.from = {0, 1, 4};
  d.camera.to = {0, 0.8, 0};
  d.camera.fov_degrees = fov;
  const uint32_t grey = add_material(d, "grey", DiffuseMaterialDesc{Rgb(0.6f)});
  const uint32_t shiny = add_material(d, "shiny", ConductorMaterialDesc{0.3, Rgb(0.2f), Rgb(3.f)});
  add_quad(d, {-3, 0, 3}, {6, 0, 0}, {0, 0, -6}, grey);
  add_quad(d, {-3, 0, -2}, {6, 0, 0}, {0, 3, 0}, shiny);
  add_quad(d, {-0.3, 1.6, -0.3}, {0.6, 0, 0}, {0, 0, 0.6}, grey);
  add_light(d, SpotLightDesc{{0.1, 2.6, 0.0}, normalize(Vec3d(0, -1, 0.1)), Rgb(30.f), 25.0, 20.0});
  add_light(d, PointLightDesc{{-1.2, 0.6, 0.8}, Rgb(0.3f, 0.2f, 0.1f), 0.05});
  add_medium(d, "fog", fog_box(Rgb(0.05f), Rgb(0.35f, 0.3f, 0.25f), 0.4, {-3, 0, -2}, {3, 3, 2}));
  return d;
}

RenderOptions traced_from(int events) {
  RenderOptions o;
  o.light_traced_from = events;
  return o;
}

TEST(LightTracing, RendersTheSameExpectedImage) {
  // A wide field of view: the camera's importance falls off as 1 / cos^3
  // toward the corners (cos 0.64 there).
  const Scene scene = build_scene(fog_pool_scene(FilterType::Box, 6, 80));
  const EstimatorNoise noise = expect_estimators_agree(scene, traced_from(3), traced_from(0));
  // The deep paths' noise is what light tracing is for (the bench measures
  // time against error).
  EXPECT_LT(noise.median_ratio, 0.9);
}

TEST(LightTracing, SpreadsSplatsOverTheGaussianFilter) {
  // The filter's weights around a splat must integrate as the camera's
  // filter-sampled rays do, or tiles would differ.
  const Scene scene = build_scene(fog_pool_scene(FilterType::Gaussian));
  expect_estimators_agree(scene, traced_from(2), traced_from(0));
}

TEST(LightTracing, LeavesPathsFromOtherLightsToTheCameraPaths) {
  // An environment light: the light tracer does not start there, so the
  // camera paths must keep its deep paths (and cannot end early).
  SceneDescription d = fog_pool_scene(FilterType::Box, 5);
  EnvironmentLightDesc sky;
  sky.radiance = Rgb(0.3f, 0.35f, 0.5f);
  add_light(d, sky);
  const Scene scene = build_scene(d);
  expect_estimators_agree(scene, traced_from(3), traced_from(0));
}

TEST(LightTracing, SplatsGoToTheirTransportAovs) {
  // From two events on, the light tracer takes all of volume_indirect and
  // diffuse_indirect (but the metal wall's, and the environment's) from the
  // lights it starts at: these AOVs compare its estimate with the camera
  // paths' alone, undiluted. A wide field of view tests the camera's
  // importance toward the corners.
  SceneDescription d = fog_pool_scene(FilterType::Gaussian, 5, 80);
  d.render.aovs = {Aov::VolumeIndirect, Aov::DiffuseIndirect};
  d.render.spp = 192;  // a 1 / cos^2 importance measured |t| 11 in a corner tile
  const Scene scene = build_scene(d);
  for (const char* aov : {"volume_indirect", "diffuse_indirect"}) {
    SCOPED_TRACE(aov);
    expect_estimators_agree(scene, traced_from(2), scene, traced_from(0), 10, 6, aov);
  }
}

TEST(LightTracing, BitwiseIdenticalForOneAndTwoThreads) {
  const Scene scene = build_scene(fog_pool_scene(FilterType::Gaussian));
  RenderOptions on = traced_from(3), off = traced_from(0);
  on.spp = off.spp = 4;
  const LayeredImage img = expect_same_bits_on_one_and_two_threads(scene, on);
  // And the splats are in it (the test can fail).
  EXPECT_NE(img.pixels, render(scene, off).image.pixels);
}

TEST(LightTracing, SampleRangesMergeBitwiseToTheFullRender) {
  // Each sample index traces its own subpaths, and their splats are added
  // to the pixel's exact sums (stream sums too, for the variance).
  SceneDescription d = fog_pool_scene(FilterType::Gaussian);
  d.render.aovs = {Aov::VolumeIndirect, Aov::Variance};
  RenderOptions full = traced_from(3);
  full.spp = 7;
  full.layer_variance = true;
  expect_ranges_merge_bitwise(build_scene(d), full, 3);
}

TEST(LightTracing, StreamSumsAddUpToTheirChannels) {
  // Each streamed channel's stream sums must add up to its sum, splats
  // included: volume_direct gets no splats (and no splat sums), the beauty
  // and volume_indirect do, in their own columns.
  SceneDescription d = fog_pool_scene(FilterType::Gaussian);
  d.render.aovs = {Aov::VolumeDirect, Aov::VolumeIndirect, Aov::Variance};
  RenderOptions o = traced_from(2);
  o.spp = 6;
  o.keep_sums = true;
  o.layer_variance = true;
  const FilmSums film = render(build_scene(d), o).film;
  ASSERT_GE(film.streamed.size(), 9u);
  const size_t nc = film.channels.size(), ns = film.streamed.size();
  for (size_t p = 0; p < film.pixel_count(); ++p)
    for (size_t j = 0; j < ns; ++j) {
      ExactSum total = 0;
      for (size_t s = 0; s < size_t(kSampleStreams); ++s)
        total += film.stream_sums[(p * kSampleStreams + s) * ns + j];
      ASSERT_TRUE(total == film.sums[p * nc + size_t(film.streamed[j])])
          << "pixel " << p << " channel " << film.channels[size_t(film.streamed[j])];
    }
}

TEST(LightTracing, StaysOffUnderTheIndirectClamp) {
  // render.clamp bounds each camera sample's indirect light; splats are not
  // camera samples, so light tracing must not run (or pixels of an indirect
  // AOV would pass the clamp).
  SceneDescription d = fog_pool_scene(FilterType::Box);
  d.render.aovs = {Aov::VolumeIndirect};
  const Scene scene = build_scene(d);
  RenderOptions o = traced_from(2);
  o.spp = 8;
  o.clamp = 0.02;
  const LayeredImage img = render(scene, o).image;
  const int c = img.channel_index("volume_indirect.R");
  ASSERT_GE(c, 0);
  float peak = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int k = 0; k < 3; ++k) peak = std::max(peak, img.at(x, y, size_t(c + k)));
  EXPECT_LE(peak, 0.02f * (1 + 1e-5f));
  EXPECT_GT(peak, 0.f);
}

TEST(LightTracing, RunsByDefaultWhereALightSitsInTheFog) {
  EXPECT_TRUE(light_tracing_pays_off(build_scene(fog_pool_scene(FilterType::Box))));
  SceneDescription above = fog_pool_scene(FilterType::Box);
  above.media.clear();
  add_medium(above, "fog",
             fog_box(Rgb(0.05f), Rgb(0.3f), 0.4, {-3, 0, -2}, {3, 0.5, 2}));  // below both lights
  EXPECT_FALSE(light_tracing_pays_off(build_scene(above)));
  SceneDescription clear = fog_pool_scene(FilterType::Box);
  clear.media.clear();
  EXPECT_FALSE(light_tracing_applies(build_scene(clear)));
  SceneDescription inside = fog_pool_scene(FilterType::Box);
  inside.camera.from = {0, 1, 1.5};
  EXPECT_FALSE(light_tracing_pays_off(build_scene(inside)));
  SceneDescription lens = fog_pool_scene(FilterType::Box);
  lens.camera.aperture = 0.1;
  EXPECT_FALSE(light_tracing_applies(build_scene(lens)));
}

}  // namespace
}  // namespace vesper::test
