// Photon merging (photon_merging.h), opt-in and biased: with a radius small
// against the fog's features its image agrees with the exact estimator's
// within the noise, tile by tile; it is deterministic, its sample ranges
// merge exactly, and the image's metadata says it ran.
#include <gtest/gtest.h>

#include "estimator_agreement.h"
#include "range_merge.h"
#include "renderer/integrator/light_tracer.h"
#include "renderer/output/metadata_keys.h"
#include "scene_fixtures.h"

namespace vesper::test {
namespace {

// A spot light's shaft onto a diffuse floor in fog, a point light beside
// it and a dim sky the photons do not start at (its deep paths stay with
// the camera paths).
SceneDescription shaft_scene(int max_depth = 5) {
  SceneDescription d = empty_scene(24, 24, 48, max_depth);
  d.camera.from = {0, 1, 4};
  d.camera.to = {0, 0.8, 0};
  d.camera.fov_degrees = 50;
  const uint32_t grey = add_material(d, "grey", DiffuseMaterialDesc{Rgb(0.6f)});
  add_quad(d, {-3, 0, 3}, {6, 0, 0}, {0, 0, -6}, grey);
  add_quad(d, {-3, 0, -2}, {6, 0, 0}, {0, 3, 0}, grey);
  add_light(d, SpotLightDesc{{0.1, 2.6, 0.0}, normalize(Vec3d(0, -1, 0.1)), Rgb(30.f), 25.0, 20.0});
  add_light(d, PointLightDesc{{-1.2, 0.6, 0.8}, Rgb(0.6f, 0.4f, 0.2f), 0.05});
  EnvironmentLightDesc sky;
  sky.radiance = Rgb(0.05f, 0.06f, 0.08f);
  add_light(d, sky);
  add_medium(d, "fog", fog_box(Rgb(0.05f), Rgb(0.35f, 0.3f, 0.25f), 0.4, {-3, 0, -2}, {3, 3, 2}));
  return d;
}

RenderOptions merging(double radius) {
  RenderOptions o;
  o.photon_merging = true;
  o.photon_radius = radius;
  return o;
}

RenderOptions exact() {
  RenderOptions o;
  o.light_traced_from = 0;
  return o;
}

TEST(PhotonMerging, AgreesWithTheExactEstimatorAtASmallRadius) {
  // volume_indirect and diffuse_indirect: photon merging takes all of them
  // from the two lights it starts at (not the sky's), so the comparison is
  // undiluted. The kernels' bias at this radius is below the tiles' noise;
  // the test catches their normalisation (a sigma_s, volume or area factor)
  // and the phase function's or the BSDF's direction.
  SceneDescription d = shaft_scene();
  d.render.aovs = {Aov::VolumeIndirect, Aov::DiffuseIndirect};
  d.render.spp = 64;
  const Scene scene = build_scene(d);
  for (const char* aov : {"volume_indirect", "diffuse_indirect"}) {
    SCOPED_TRACE(aov);
    expect_estimators_agree(scene, merging(0.05), scene, exact(), 10, 6, aov);
  }
  expect_estimators_agree(scene, merging(0.05), exact());  // and the beauty
}

TEST(PhotonMerging, BitwiseIdenticalForOneAndTwoThreads) {
  const Scene scene = build_scene(shaft_scene());
  // Enough subpaths (18 tasks of 1024) that two threads finish them out of
  // order: joining the photons in finishing order fails this test.
  RenderOptions on = merging(0.1), off = exact();
  on.spp = off.spp = 32;
  const LayeredImage img = expect_same_bits_on_one_and_two_threads(scene, on);
  EXPECT_NE(img.pixels, render(scene, off).image.pixels);  // the photons are in it
}

TEST(PhotonMerging, SampleRangesMergeBitwiseToTheFullRender) {
  // Every range traces the whole frame's photons, so each reads the same.
  SceneDescription d = shaft_scene();
  d.render.aovs = {Aov::VolumeIndirect, Aov::Variance};
  RenderOptions full = merging(0.1);
  full.spp = 7;
  full.layer_variance = true;
  expect_ranges_merge_bitwise(build_scene(d), full, 3);
}

TEST(PhotonMerging, TheImageSaysItRan) {
  const Scene scene = build_scene(shaft_scene());
  RenderOptions o = merging(0.1);
  o.spp = 2;
  const LayeredImage img = render(scene, o).image;
  ASSERT_TRUE(img.metadata.count(metadata_key::kPhotonMerging));
  EXPECT_EQ(img.metadata.at(metadata_key::kPhotonMerging).rfind("radius 0.1 photons ", 0), 0u)
      << img.metadata.at(metadata_key::kPhotonMerging);
  RenderOptions off = exact();
  off.spp = 2;
  EXPECT_FALSE(render(scene, off).image.metadata.count(metadata_key::kPhotonMerging));
  // Without media it cannot run, and says nothing.
  SceneDescription clear = shaft_scene();
  clear.media.clear();
  EXPECT_FALSE(photon_merging_applies(build_scene(clear)));
  EXPECT_FALSE(render(build_scene(clear), o).image.metadata.count(metadata_key::kPhotonMerging));
}

}  // namespace
}  // namespace vesper::test
