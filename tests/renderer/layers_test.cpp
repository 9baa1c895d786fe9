// Layers and transport AOVs: partitions of the beauty's paths add up to the
// beauty (same paths, so to float rounding), variant layers equal renders of
// the modified scene, and only the requested layers are computed.
#include <gtest/gtest.h>

#include "render_stats.h"
#include "renderer/render/frame.h"
#include "scene_fixtures.h"
#include "test_grids.h"

namespace vesper::test {
namespace {

// Fog, a glowing VDB, three light groups, principled + glass + metal.
SceneDescription layered_scene() {
  SceneDescription d = small_cornell(24, 24, 8);
  d.render.max_depth = 6;
  d.lights[0].group = "ceiling";
  add_light(d, PointLightDesc{{0.5, 0.8, 0.6}, Rgb(0.8f, 0.5f, 0.2f)}, "candles");
  add_light(d,
            SpotLightDesc{{-0.5, 1.8, 0.5}, normalize(Vec3d(0.3, -1, -0.2)), Rgb(3.f), 30.0, 20.0},
            "window");
  const uint32_t plastic =
      add_material(d, "plastic", PrincipledMaterialDesc{Rgb(0.2f, 0.4f, 0.8f), 0.2, 0.3});
  const uint32_t glass = add_material(d, "glass", DielectricMaterialDesc{1.5, 0.0});
  add_sphere(d, {0.0, 1.2, -0.4}, 0.25, plastic);
  add_sphere(d, {-0.1, 0.25, 0.5}, 0.2, glass);
  add_medium(d, "fog", fog_box(Rgb(0.05f), Rgb(0.6f), 0.3, {-1, 0, -1}, {1, 2, 1}));
  VdbMediumDesc glow;
  glow.file = "glow";
  glow.density = std::make_shared<FunctionGrid>(9, 0.05, Vec3d(0.3, 0.2, -0.2),
                                                [](const Vec3&) { return 1.f; });
  glow.emission = glow.density;
  glow.emission_grid = "density";
  glow.emission_scale = 2.0;
  glow.emission_color = Rgb(1.f, 0.6f, 0.2f);
  glow.sigma_s = Rgb(2.f);
  add_medium(d, "glow", glow);
  return d;
}

LayerDesc layer(std::string name, PathSelection paths,
                std::optional<std::vector<std::string>> lights = {}) {
  LayerDesc l;
  l.name = std::move(name);
  l.paths = paths;
  l.lights = std::move(lights);
  return l;
}

// max over pixels and RGB of |sum of the layers - beauty| / max(|beauty|, 1e-3)
double max_partition_error(const LayeredImage& img, const std::vector<std::string>& parts) {
  double worst = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const char* rgb[3] = {".R", ".G", ".B"};
        double sum = 0;
        for (const auto& p : parts) {
          const int ch = img.channel_index(p + rgb[c]);
          EXPECT_GE(ch, 0) << p;
          if (ch >= 0) sum += img.at(x, y, size_t(ch));
        }
        const double beauty = img.at(x, y, size_t(c));
        worst = std::max(worst, std::abs(sum - beauty) / std::max(std::abs(beauty), 1e-3));
      }
  return worst;
}

TEST(Layers, SurfaceAndVolumePathsPartitionTheBeauty) {
  SceneDescription d = layered_scene();
  d.layers = {layer("surf", PathSelection::Surface), layer("vol", PathSelection::Volume)};
  const FrameResult f = render_frame(d);
  EXPECT_LT(max_partition_error(f.image, {"surf", "vol"}), 1e-5);
  // Both parts carry light (the test is not trivially satisfied).
  EXPECT_GT(max_partition_error(f.image, {"surf"}), 0.05);
  EXPECT_GT(max_partition_error(f.image, {"vol"}), 0.05);
}

TEST(Layers, LightGroupsPartitionTheBeauty) {
  SceneDescription d = layered_scene();
  d.layers = {layer("g_ceiling", PathSelection::All, std::vector<std::string>{"ceiling"}),
              layer("g_candles", PathSelection::All, std::vector<std::string>{"candles"}),
              layer("g_window", PathSelection::All, std::vector<std::string>{"window"}),
              layer("g_emission", PathSelection::All, std::vector<std::string>{"emission"})};
  const FrameResult f = render_frame(d);
  EXPECT_LT(max_partition_error(f.image, {"g_ceiling", "g_candles", "g_window", "g_emission"}),
            1e-5);
  EXPECT_GT(max_partition_error(f.image, {"g_ceiling", "g_candles", "g_window"}),
            1e-3);  // emission matters
}

TEST(Layers, TransportAovsPartitionTheBeauty) {
  SceneDescription d = layered_scene();
  d.render.aovs = {Aov::Emission,       Aov::DiffuseDirect,    Aov::DiffuseIndirect,
                   Aov::SpecularDirect, Aov::SpecularIndirect, Aov::VolumeDirect,
                   Aov::VolumeIndirect};
  const FrameResult f = render_frame(d);
  const std::vector<std::string> all = {"emission",        "diffuse_direct",    "diffuse_indirect",
                                        "specular_direct", "specular_indirect", "volume_direct",
                                        "volume_indirect"};
  EXPECT_LT(max_partition_error(f.image, all), 1e-5);
  for (const auto& name : all) {  // every AOV receives some light in this scene
    std::vector<std::string> others;
    for (const auto& n : all)
      if (n != name) others.push_back(n);
    EXPECT_GT(max_partition_error(f.image, others), 1e-4) << name << " is empty";
  }
}

TEST(Layers, WithoutMediaVolumeLayersAreZeroAndOnlyRequestedLayersExist) {
  SceneDescription d = small_cornell(16, 16, 4);
  d.layers = {layer("fog", PathSelection::Volume), layer("rest", PathSelection::Surface)};
  const FrameResult f = render_frame(d);
  const std::vector<std::string> expected = {"R",     "G",     "B",      "A",      "fog.R",
                                             "fog.G", "fog.B", "rest.R", "rest.G", "rest.B"};
  std::vector<std::string> channels = f.image.channels;
  EXPECT_EQ(channels, expected);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 4; c < 7; ++c) EXPECT_EQ(f.image.at(x, y, size_t(c)), 0.f);
  EXPECT_LT(max_partition_error(f.image, {"rest"}), 1e-6);
}

TEST(Layers, NoLayersMeansNoExtraChannels) {
  const FrameResult f = render_frame(small_cornell(8, 8, 1));
  EXPECT_EQ(f.image.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(f.passes, 1);
}

TEST(Layers, VariantLayerEqualsARenderOfTheModifiedScene) {
  SceneDescription d = layered_scene();
  LayerDesc dense = layer("rays_dense", PathSelection::Volume, std::vector<std::string>{"window"});
  VariantDesc v;
  MediumOverride o;
  o.sigma_s = Rgb(2.4f);
  v.media["fog"] = o;
  MediumOverride glow_off;
  glow_off.density_scale = 4.0;
  v.media["glow"] = glow_off;
  v.lights = std::vector<std::string>{"window"};
  dense.variant = v;
  d.layers = {dense};
  const FrameResult f = render_frame(d);
  EXPECT_EQ(f.passes, 2);

  // The same scene written out by hand: denser fog, only the window light.
  SceneDescription by_hand = d;
  by_hand.layers.clear();
  std::get<HomogeneousMediumDesc>(by_hand.media[0].medium).sigma_s = Rgb(2.4f);
  std::get<VdbMediumDesc>(by_hand.media[1].medium).density_scale = 4.0;
  std::get<VdbMediumDesc>(by_hand.media[1].medium).emission_scale =
      0;  // "emission" is not an active group
  for (auto& l : by_hand.lights)
    if (l.group != "window") {
      if (auto* q = std::get_if<QuadLightDesc>(&l.light)) q->radiance = Rgb{};
      if (auto* p = std::get_if<PointLightDesc>(&l.light)) p->intensity = Rgb{};
    }
  by_hand.layers = {layer("ref", PathSelection::Volume, std::vector<std::string>{"window"})};
  const FrameResult r = render_frame(by_hand);
  // Same scene, same seed, same paths: equal to float rounding of the light
  // sampler's normalisation... in fact bitwise, since the scenes are identical.
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x)
      for (int c = 0; c < 3; ++c) {
        const float a =
            f.image.at(x, y, size_t(f.image.channel_index(std::string("rays_dense.") + "RGB"[c])));
        const float b =
            r.image.at(x, y, size_t(r.image.channel_index(std::string("ref.") + "RGB"[c])));
        ASSERT_EQ(a, b) << x << "," << y << " channel " << c;
      }
  // And the variant differs from the same selection of the undensified scene.
  SceneDescription plain = layered_scene();
  plain.layers = {layer("plain", PathSelection::Volume, std::vector<std::string>{"window"})};
  const FrameResult p = render_frame(plain);
  double diff = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x)
      diff += std::abs(p.image.at(x, y, size_t(p.image.channel_index("plain.R"))) -
                       f.image.at(x, y, size_t(f.image.channel_index("rays_dense.R"))));
  EXPECT_GT(diff, 1e-3);
}

TEST(Layers, VariantDensityOverrideMatchesASceneWithThatDensity) {
  // The Z-test form of the variant check: independent seeds.
  SceneDescription d = layered_scene();
  d.media.erase(d.media.begin() + 1);  // the fog alone
  LayerDesc thick = layer("thick", PathSelection::All);
  VariantDesc v;
  MediumOverride o;
  o.sigma_s = Rgb(1.5f);
  v.media["fog"] = o;
  thick.variant = v;
  d.layers = {thick};
  SceneDescription reference = d;
  reference.layers.clear();
  std::get<HomogeneousMediumDesc>(reference.media[0].medium).sigma_s = Rgb(1.5f);
  const int batches = 10, tile = 6;
  std::vector<double> a(16, 0), a2(16, 0), b(16, 0), b2(16, 0);
  for (int k = 0; k < batches; ++k) {
    RenderOptions o1, o2;
    o1.seed = 100 + uint64_t(k);
    o2.seed = 900 + uint64_t(k);
    const FrameResult f = render_frame(d, o1);
    const RenderResult r = render(build_scene(reference), o2);
    const int ch = f.image.channel_index("thick.G");
    std::vector<double> ta(16, 0), tb(16, 0);
    for (int y = 0; y < 24; ++y)
      for (int x = 0; x < 24; ++x) {
        ta[size_t((y / tile) * 4 + x / tile)] += f.image.at(x, y, size_t(ch));
        tb[size_t((y / tile) * 4 + x / tile)] += r.image.at(x, y, 1);
      }
    for (size_t t = 0; t < 16; ++t) {
      a[t] += ta[t];
      a2[t] += ta[t] * ta[t];
      b[t] += tb[t];
      b2[t] += tb[t] * tb[t];
    }
  }
  const double crit = sidak_t_critical(0.01, 16, batches - 1);
  for (size_t t = 0; t < 16; ++t) {
    const double ma = a[t] / batches, mb = b[t] / batches;
    const double va = (a2[t] / batches - ma * ma) / (batches - 1),
                 vb = (b2[t] / batches - mb * mb) / (batches - 1);
    EXPECT_LT(std::abs(ma - mb) / std::sqrt(std::max(va + vb, 1e-18)), crit) << "tile " << t;
  }
}

TEST(Layers, DensityScaleOnHomogeneousFogScalesItsCoefficients) {
  SceneDescription d = layered_scene();
  LayerDesc l = layer("dense", PathSelection::All);
  VariantDesc v;
  MediumOverride o;
  o.density_scale = 3.0;
  v.media["fog"] = o;
  l.variant = v;
  d.layers = {l};
  const SceneDescription variant = apply_variant(d, *l.variant);
  const auto& fog = std::get<HomogeneousMediumDesc>(variant.media[0].medium);
  EXPECT_FLOAT_EQ(fog.sigma_s.g, 1.8f);
  EXPECT_FLOAT_EQ(fog.sigma_a.g, 0.15f);
  EXPECT_TRUE(variant.layers.empty());
}

TEST(Layers, LayerAlphaIsOneMinusCameraTransmittance) {
  // Homogeneous slab in front of a wall: transmittance is analytic and exact.
  SceneDescription d = empty_scene(8, 8, 2, 2);
  d.camera.from = {0, 0, 5};
  d.camera.to = {0, 0, 0};
  d.camera.fov_degrees = 2;
  add_quad(d, {-5, -5, -1}, {10, 0, 0}, {0, 10, 0},
           add_material(d, "wall", DiffuseMaterialDesc{Rgb(0.5f)}));
  add_light(d, EnvironmentLightDesc{});
  add_medium(d, "fog", fog_box(Rgb(0.2f), Rgb(0.3f), 0.0, {-5, -5, 0}, {5, 5, 2}));
  d.layers = {layer("fog", PathSelection::Volume)};
  const FrameResult f = render_frame(d);
  const int a = f.image.channel_index("fog.A");
  ASSERT_GE(a, 0);
  const double expect =
      1.0 - std::exp(-0.5 * 2.0);  // straight through 2 units (rays within 0.1 deg)
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) EXPECT_NEAR(f.image.at(x, y, size_t(a)), expect, 1e-3);
}

}  // namespace
}  // namespace vesper::test
