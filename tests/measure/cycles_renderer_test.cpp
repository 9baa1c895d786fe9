// cycles_renderer: Blender Cycles run through bench/cycles/vesper_to_cycles.py
// agrees with analytic radiance (so units and conventions translate), refuses
// what it cannot translate naming the JSON path, and says how to install a
// missing blender. The tests that render skip (with the reason) without blender.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "measure/cycles_renderer.h"

namespace vesper::measure {
namespace {
namespace fs = std::filesystem;

// Two-sided z for alpha = 1e-3: a correct translation fails 1 run in 1000.
constexpr double kZCritical = 3.29;
constexpr double kPi = 3.14159265358979323846;

fs::path test_dir(const std::string& name) {
  const fs::path dir = fs::path(VESPER_TEST_ARTIFACT_DIR) / "cycles" / name;
  fs::create_directories(dir);
  return dir;
}

CyclesRendererOptions options(const std::string& name) {
  CyclesRendererOptions o;
  o.script = std::string(VESPER_SOURCE_DIR) + "/bench/cycles/vesper_to_cycles.py";
  o.work_dir = (test_dir(name) / "work").string();
  return o;
}

BenchScene write_scene(const std::string& name, const std::string& json, int size) {
  const fs::path path = test_dir(name) / "scene.json";
  std::ofstream(path) << json;
  return BenchScene{name, path.string(), "surface", size, size};
}

#define SKIP_WITHOUT_BLENDER()            \
  if (find_executable("blender").empty()) \
  GTEST_SKIP() << "blender is not installed (benchmark-only peer: scripts/setup --peers)"

// A camera 2 units above an endless grey floor (albedo 0.5), looking down,
// 60-degree fov: it sees only floor. max_depth 1 = direct light only.
std::string floor_scene(const std::string& lights) {
  return R"({"format": "vesper-scene/1",
  "camera": {"type": "perspective", "from": [0, 2, 0], "to": [0, 0, 0], "up": [0, 0, -1], "fov": 60},
  "film": {"width": 16, "height": 16},
  "render": {"spp": 16, "max_depth": 1},
  "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
  "shapes": [{"type": "quad", "corner": [-100, 0, 100], "edge1": [200, 0, 0], "edge2": [0, 0, -200],
              "material": "grey"}],
  "lights": [)" +
         lights + "]}";
}

// Blender 3.4's status lines (stdout in background mode), as the progress bar reads them.
TEST(CyclesRenderer, ProgressReadsTheLastSampleStatus) {
  EXPECT_EQ(last_sample_status(""), (std::pair<size_t, size_t>{0, 0}));
  EXPECT_EQ(last_sample_status("Fra:1 Mem:8.1M | Time:00:00.10 | Syncing Sphere\n"),
            (std::pair<size_t, size_t>{0, 0}));
  const std::string lines =
      "Fra:1 Mem:18.61M (Peak 19.51M) | Time:00:00.53 | Remaining:00:00.27 | Mem:2.73M, "
      "Peak:2.73M | Scene, ViewLayer | Sample 40/64\n"
      "Fra:1 Mem:18.61M (Peak 19.51M) | Time:00:00.61 | Remaining:00:00.19 | Mem:2.73M, "
      "Peak:2.73M | Scene, ViewLayer | Sample 48/64\n"
      "Fra:1 Mem:18.61M | Time:00:00.70 | Mem:2.73M | Scene, ViewLayer | Sample 51";
  EXPECT_EQ(last_sample_status(lines),
            (std::pair<size_t, size_t>{48, 64}));  // the torn line skipped
}

TEST(CyclesRenderer, MissingBlenderSaysHowToInstallIt) {
  CyclesRendererOptions o = options("missing");
  for (const std::string blender : {"/nonexistent/blender", "vesper-no-such-blender"}) {
    o.blender = blender;
    try {
      cycles_renderer(o);
      FAIL() << "expected an error for " << blender;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("scripts/setup --peers"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(blender), std::string::npos) << e.what();
    }
  }
}

// Sun (irradiance E, from straight above) plus a constant sky L_env over a
// Lambertian floor: every pixel's expected radiance is albedo (L_env + E/pi).
// The sky's hemisphere sampling is the noise; pixels are independent, so the
// image mean is Z-tested against that value with the pixels' own spread.
TEST(CyclesRenderer, SunAndSkyOnADiffuseFloorMatchTheAnalyticRadiance) {
  SKIP_WITHOUT_BLENDER();
  const BenchRenderer cycles = cycles_renderer(options("sun-sky"));
  EXPECT_EQ(cycles.name, "cycles");
  EXPECT_NE(cycles.cache_key.find("Blender "), std::string::npos) << cycles.cache_key;
  const BenchScene scene = write_scene("sun-sky", floor_scene(R"(
    {"type": "sun", "direction": [0, 1, 0], "irradiance": [3, 2, 1], "angle": 0},
    {"type": "environment", "radiance": [0.4, 0.2, 0.8]})"),
                                       16);
  const RenderedImage r = cycles.render(scene, 16, 7, 2);
  ASSERT_EQ(r.image.width, 16);
  EXPECT_GT(r.render_seconds, 0.0);
  EXPECT_GE(r.wall_seconds, r.render_seconds);
  const double sun[3] = {3, 2, 1}, sky[3] = {0.4, 0.2, 0.8};
  for (int c = 0; c < 3; ++c) {
    const int channel = r.image.channel_index(std::string(1, "RGB"[c]));
    ASSERT_GE(channel, 0);
    const double expected = 0.5 * (sky[c] + sun[c] / kPi);
    double sum = 0, sum2 = 0;
    const int n = r.image.width * r.image.height;
    for (int y = 0; y < r.image.height; ++y)
      for (int x = 0; x < r.image.width; ++x) {
        const double v = r.image.at(x, y, size_t(channel));
        sum += v;
        sum2 += v * v;
      }
    const double mean = sum / n, var = std::max(sum2 / n - mean * mean, 0.0);
    // A floor for the standard error: a noiseless image is exact to float rounding.
    const double se = std::max(std::sqrt(var / (n - 1)), 1e-6 * expected);
    EXPECT_LT(std::abs(mean - expected) / se, kZCritical)
        << "channel "
        << "RGB"[c] << ": mean " << mean << ", analytic " << expected << ", se " << se;
  }
}

// A spot light (intensity I, 70-degree cone, no falloff) 1 unit above the
// floor: L(x) = albedo/pi * I * h / d^3. Cycles 3.4 adds a cos(theta) the
// script cancels; without the cancellation the image is ~20% dark here. Each
// pixel's expectation and variance over its area (box filter) come from
// 16x16 quadrature; the mean difference is Z-tested with that variance.
TEST(CyclesRenderer, SpotLightOnADiffuseFloorMatchesTheAnalyticRadiance) {
  SKIP_WITHOUT_BLENDER();
  const BenchRenderer cycles = cycles_renderer(options("spot"));
  const BenchScene scene = write_scene("spot", floor_scene(R"(
    {"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "intensity": [2, 2, 2],
     "cone_angle": 70})"),
                                       16);
  const int spp = 16;
  const RenderedImage r = cycles.render(scene, spp, 3, 2);
  const int channel = r.image.channel_index("G");
  ASSERT_GE(channel, 0);
  const double half_width = 2.0 * std::tan(30.0 * kPi / 180.0);  // floor seen: [-hw, hw]^2
  const auto radiance = [](double x, double z) {
    const double d = std::sqrt(x * x + z * z + 1.0);
    return 0.5 / kPi * 2.0 / (d * d * d);
  };
  double diff = 0, var_sum = 0;
  const int n = 16, q = 16;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      double m = 0, m2 = 0;
      for (int b = 0; b < q; ++b)
        for (int a = 0; a < q; ++a) {
          // Image right is +X, image down is +Z (up hint -Z).
          const double x = (2.0 * (i + (a + 0.5) / q) / n - 1.0) * half_width;
          const double z = (2.0 * (j + (b + 0.5) / q) / n - 1.0) * half_width;
          const double v = radiance(x, z);
          m += v;
          m2 += v * v;
        }
      m /= q * q;
      var_sum += std::max(m2 / (q * q) - m * m, 0.0) / spp;
      diff += r.image.at(i, j, size_t(channel)) - m;
    }
  const double mean_diff = diff / (n * n), se = std::sqrt(var_sum) / (n * n);
  EXPECT_LT(std::abs(mean_diff) / se, kZCritical)
      << "mean difference " << mean_diff << ", se " << se;
}

TEST(CyclesRenderer, AnUntranslatableSceneThrowsNamingTheJsonPath) {
  SKIP_WITHOUT_BLENDER();
  const BenchRenderer cycles = cycles_renderer(options("keyed"));
  std::string json =
      floor_scene(R"({"type": "sun", "direction": [0, 1, 0], "irradiance": [1, 1, 1]})");
  const std::string fov = "\"fov\": 60";
  json.replace(json.find(fov), fov.size(), R"("fov": {"keys": [[1, 40], [24, 60]]})");
  const BenchScene scene = write_scene("keyed", json, 16);
  try {
    cycles.render(scene, 1, 0, 1);
    FAIL() << "a keyed camera was rendered";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/camera/fov"), std::string::npos) << what;
    EXPECT_NE(what.find("cycles"), std::string::npos) << what;
    EXPECT_NE(what.find("exit code 2"), std::string::npos) << what;
    EXPECT_NE(what.find(scene.scene_path), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace vesper::measure
