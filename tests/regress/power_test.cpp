// Power: real changes are flagged, naming the layer and a region that
// contains the changed area, while a control (the unchanged scene, another
// seed, same spp) passes. Changed scenes render with other seeds than the
// golden, so their noise is independent, as the test assumes. Each test
// prints the smallest change it could have detected at that noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "regress/compare.h"
#include "render_fixtures.h"

namespace vesper::test {
namespace {

using regress::LayerResult;
using regress::SceneResult;
using regress::Verdict;

std::string reasons_of(const SceneResult& r) {
  std::string s;
  for (const std::string& line : r.reasons) s += "\n  " + line;
  return s;
}

const LayerResult* layer(const SceneResult& r, const std::string& name) {
  for (const LayerResult& l : r.layers)
    if (l.layer == name) return &l;
  return nullptr;
}

bool intersects(const regress::Region& r, int x0, int y0, int x1, int y1) {
  return r.x < x1 && x0 < r.x + r.width && r.y < y1 && y0 < r.y + r.height;
}

// The most significant region no larger than a tile: where the change is.
const regress::Region* worst_tile(const LayerResult& l) {
  for (const regress::Region& r : l.worst)
    if (r.width <= l.tile_size && r.height <= l.tile_size) return &r;
  return nullptr;
}

void print_figures(const char* label, const SceneResult& r) {
  const LayerResult& b = *layer(r, "beauty");
  std::printf(
      "%s: %s, max |Z| %.2f, detectable change %.2f %% per tile, %.2f %% over the frame%s\n", label,
      regress::verdict_name(r.verdict), b.max_abs_z, 100 * b.min_detectable_change,
      100 * b.frame_detectable_change, reasons_of(r).c_str());
}

SceneResult expect_pass(const LayeredImage& golden, const LayeredImage& fresh, const char* label) {
  const SceneResult r = regress::compare_frames(golden, fresh, nullptr, {});
  print_figures(label, r);
  EXPECT_EQ(r.verdict, Verdict::Pass) << label << reasons_of(r);
  return r;
}

// Regressed in the beauty, the worst tile inside [x0, x1) x [y0, y1).
SceneResult expect_beauty_region(const LayeredImage& golden, const LayeredImage& fresh,
                                 const char* label, int x0, int y0, int x1, int y1) {
  const SceneResult r = regress::compare_frames(golden, fresh, nullptr, {});
  print_figures(label, r);
  EXPECT_EQ(r.verdict, Verdict::Regressed) << label << reasons_of(r);
  const LayerResult* b = layer(r, "beauty");
  EXPECT_EQ(b->verdict, Verdict::Regressed) << label;
  const regress::Region* w = worst_tile(*b);
  EXPECT_TRUE(w && intersects(*w, x0, y0, x1, y1))
      << label << ": worst tile "
      << (w ? std::to_string(w->x) + "," + std::to_string(w->y) : "none");
  bool named = false;
  for (const std::string& line : r.reasons) named |= line.rfind("beauty: ", 0) == 0;
  EXPECT_TRUE(named) << label << reasons_of(r);
  return r;
}

void remove_channels(LayeredImage& img, const std::string& prefix) {
  LayeredImage out = img;
  out.channels.clear();
  out.pixels.clear();
  std::vector<size_t> keep;
  for (size_t c = 0; c < img.channels.size(); ++c)
    if (img.channels[c].rfind(prefix, 0) != 0)
      keep.push_back(c), out.channels.push_back(img.channels[c]);
  for (size_t p = 0; p < size_t(img.width) * size_t(img.height); ++p)
    for (size_t c : keep) out.pixels.push_back(img.pixels[p * img.channels.size() + c]);
  img = std::move(out);
}

// The Cornell box at 64x64, 256 spp. Its ceiling light's image covers about
// x 25-39, y 5-10, across the border of two 16-pixel tiles.
TEST(Power, CornellLightMovedNanPixelMissingLayerAndChannel) {
  const SceneDescription scene = cornell(64, 64, 256);
  const LayeredImage golden = render_with_variance(scene, 1000);
  const LayeredImage control = render_with_variance(scene, 1);
  expect_pass(golden, control, "cornell control");

  SceneDescription moved = scene;  // 1 % of the 2-unit box, sideways
  std::get<QuadLightDesc>(moved.lights[0].light).corner.x += 0.02;
  expect_beauty_region(golden, render_with_variance(moved, 2), "cornell light moved 0.02", 25, 5,
                       40, 11);

  LayeredImage nan = control;
  nan.at(41, 17, size_t(nan.channel_index("G"))) = std::numeric_limits<float>::quiet_NaN();
  const SceneResult n = regress::compare_frames(golden, nan, nullptr, {});
  EXPECT_EQ(n.verdict, Verdict::Regressed) << reasons_of(n);
  ASSERT_EQ(layer(n, "beauty")->introduced_nonfinite, 1u);
  EXPECT_EQ(layer(n, "beauty")->introduced_nonfinite_at[0].x, 41);
  EXPECT_EQ(layer(n, "beauty")->introduced_nonfinite_at[0].y, 17);
  EXPECT_NE(reasons_of(n).find("beauty: 1 new NaN/Inf pixel (golden 0, new 1), first at (41, 17)"),
            std::string::npos)
      << reasons_of(n);

  LayeredImage no_layer = control;
  remove_channels(no_layer, "surfaces.");
  const SceneResult m = regress::compare_frames(golden, no_layer, nullptr, {});
  EXPECT_EQ(m.verdict, Verdict::Regressed);
  EXPECT_EQ(layer(m, "surfaces")->verdict, Verdict::Regressed);
  EXPECT_EQ(m.channels_missing,
            (std::vector<std::string>{"surfaces.R", "surfaces.G", "surfaces.B"}));
  EXPECT_NE(reasons_of(m).find("surfaces: missing in the new render"), std::string::npos)
      << reasons_of(m);

  LayeredImage no_channel = control;
  remove_channels(no_channel, "variance.G");
  const SceneResult c = regress::compare_frames(golden, no_channel, nullptr, {});
  EXPECT_EQ(c.verdict, Verdict::Regressed);
  EXPECT_EQ(c.channels_missing, std::vector<std::string>{"variance.G"});
  EXPECT_NE(reasons_of(c).find("beauty: channels missing: variance.G"), std::string::npos)
      << reasons_of(c);
}

// A 2 % brighter back wall, framed so the wall fills the shot above the two
// spheres (bottom corners): 48x48, 512 spp.
TEST(Power, BackWallAlbedoUpTwoPercent) {
  SceneDescription scene = cornell(48, 48, 512);
  scene.camera.from = {0, 1, 1.5};
  scene.camera.to = {0, 1, -1};
  scene.camera.fov_degrees = 40;
  const LayeredImage golden = render_with_variance(scene, 1000);
  expect_pass(golden, render_with_variance(scene, 1), "back wall control");
  SceneDescription brighter = scene;
  auto& back = std::get<DiffuseMaterialDesc>(brighter.materials.back());
  back.albedo = back.albedo * 1.02f;
  expect_beauty_region(golden, render_with_variance(brighter, 2), "back wall albedo +2 %", 0, 0, 48,
                       28);
}

// scenes/fog-shafts at 64x48, 1024 spp, single scattering (max_depth 2),
// sigma_a and sigma_s up 5 %: the shafts brighten (more in-scattering) and
// the lit floor darkens (more extinction on the light's and the camera's
// paths), so the frame's mean hardly moves; the floor's tiles (y >= 32)
// carry the change, about -4 %. With multiple scattering the denser fog also
// sends more light back to the floor, halving the change there (-2 % at
// max_depth 6, measured), and noise needs ~4000 spp to show that decisively.
TEST(Power, FogDensityUpFivePercent) {
  SceneDescription scene = fog_shafts(64, 1024);
  scene.render.max_depth = 2;
  const LayeredImage golden = render_with_variance(scene, 1000, true);
  expect_pass(golden, render_with_variance(scene, 1, true), "fog control");
  SceneDescription denser = scene;
  auto& fog = std::get<HomogeneousMediumDesc>(denser.media[0].medium);
  fog.sigma_a = fog.sigma_a * 1.05f;
  fog.sigma_s = fog.sigma_s * 1.05f;
  const SceneResult r = expect_beauty_region(golden, render_with_variance(denser, 2, true),
                                             "fog density +5 %", 0, 32, 64, 48);
  // The fog layer (volume-first paths) hardly changes: more in-scattering,
  // but more extinction of it on the way to the camera. It is tested with
  // its own variance (vesper render --layer-variance); only its figures are printed.
  const LayerResult* f = layer(r, "fog");
  ASSERT_TRUE(f && f->has_variance);
  std::printf(
      "fog layer: %s, max |Z| %.2f, detectable change %.2f %% per tile, %.2f %% over the "
      "frame\n",
      regress::verdict_name(f->verdict), f->max_abs_z, 100 * f->min_detectable_change,
      100 * f->frame_detectable_change);
}

}  // namespace
}  // namespace vesper::test
