// Motion blur over render.shutter: blurred edges against the analytic
// time-averaged coverage (per-pixel t-tests over independent renders), a
// zero-length shutter is the still frame bit for bit, and determinism and
// exact partial merges hold with motion blur.
#include <gtest/gtest.h>

#include <functional>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "renderer/core/rigid_motion.h"
#include "renderer/render/render.h"
#include "renderer/scene/scene_loader.h"
#include "tests/renderer/range_merge.h"
#include "tests/renderer/render_stats.h"

namespace vesper {
namespace {

using nlohmann::json;

constexpr double kAlpha = 1e-3;  // family-wise, Sidak over the pixels tested
constexpr int kReplicas = 24;    // independent renders (seeds) per image
constexpr int kSpp = 64;

// A camera at z = 4 looking down -z with fov 30 across the 2-pixel height:
// the plane z = 0 maps to raster x linearly (film 16 x 2, box filter).
json edge_scene() {
  return json::parse(R"({
    "format": "vesper-scene/1",
    "camera": {"type": "perspective", "from": [0, 0, 4], "to": [0, 0, 0], "up": [0, 1, 0], "fov": 30},
    "film": {"width": 16, "height": 2, "filter": "box"},
    "render": {"spp": 64, "max_depth": 1, "shutter": [0, 0.5]},
    "materials": {"black": {"type": "diffuse", "albedo": [0, 0, 0]},
                  "white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
    "shapes": []
  })");
}

// World x range [x0, x1] of pixel column i on the plane at depth `dist` from the camera.
std::pair<double, double> pixel_span(int i, int width, double dist) {
  const double tan_half_x = std::tan(15.0 * M_PI / 180.0) * width / 2.0;  // height 2
  auto x = [&](double fx) { return dist * (2.0 * fx / width - 1.0) * tan_half_x; };
  return {x(i), x(i + 1)};
}

// Mean over e uniform in [ea, eb] of the fraction of [x0, x1] left of e.
double mean_left_fraction(double x0, double x1, double ea, double eb) {
  const double w = x1 - x0;
  auto antiderivative = [&](double e) {  // of clamp((e - x0) / w, 0, 1) de
    if (e <= x0) return 0.0;
    if (e < x1) return (e - x0) * (e - x0) / (2 * w);
    return w / 2 + (e - x1);
  };
  return (antiderivative(eb) - antiderivative(ea)) / (eb - ea);
}

struct PixelStats {
  std::vector<double> mean, se;
};

// Channel R of every pixel over kReplicas renders with different seeds.
PixelStats replicate(const Scene& scene) {
  const size_t n = size_t(scene.film.width * scene.film.height);
  std::vector<std::vector<double>> v(n);
  for (int r = 0; r < kReplicas; ++r) {
    RenderOptions o;
    o.spp = kSpp;
    o.seed = 100 + uint64_t(r);
    const RenderResult res = render(scene, o);
    for (int y = 0; y < scene.film.height; ++y)
      for (int x = 0; x < scene.film.width; ++x)
        v[size_t(y * scene.film.width + x)].push_back(res.image.at(x, y, 0));
  }
  PixelStats s;
  for (const auto& samples : v) {
    double m = 0, var = 0;
    for (double x : samples) m += x;
    m /= kReplicas;
    for (double x : samples) var += (x - m) * (x - m);
    s.mean.push_back(m);
    s.se.push_back(std::sqrt(var / (kReplicas - 1) / kReplicas));
  }
  return s;
}

// Pixels whose mean disagrees with `expected(x)`: a t-test (dof kReplicas - 1)
// where the replicas vary; exact agreement (to float rounding of `scale`)
// where every sample is the same.
int rejected_pixels(const Scene& scene, double scale,
                    const std::function<double(int column)>& expected, std::string& log) {
  const PixelStats s = replicate(scene);
  const int n = int(s.mean.size());
  const double t_crit = test::sidak_t_critical(kAlpha, n, kReplicas - 1);
  int rejected = 0;
  for (int p = 0; p < n; ++p) {
    const double want = scale * expected(p % scene.film.width);
    const bool ok = s.se[size_t(p)] > 0
                        ? std::abs(s.mean[size_t(p)] - want) / s.se[size_t(p)] < t_crit
                        : std::abs(s.mean[size_t(p)] - want) <= 1e-5 * scale;
    if (!ok) {
      ++rejected;
      log += "pixel " + std::to_string(p) + ": mean " + std::to_string(s.mean[size_t(p)]) + " se " +
             std::to_string(s.se[size_t(p)]) + " expected " + std::to_string(want) + "\n";
    }
  }
  return rejected;
}

// A black quad (x >= e(t), y in [-10, 10]) in the plane z = 0 in front of a
// white environment, its edge keyed from x = -3 at frame 1 to 3 at frame 2:
// over the shutter [0, 0.5] of frame 1 it sweeps [-3, 0], about 2 pixels.
json moving_black_quad(const json& shutter) {
  json doc = edge_scene();
  doc["render"]["shutter"] = shutter;
  doc["lights"] = json::parse(R"([{"type": "environment", "radiance": [1, 1, 1]}])");
  doc["shapes"].push_back(json::parse(R"({"type": "quad", "material": "black",
      "corner": {"keys": [[1, [-3, -10, 0]], [2, [3, -10, 0]]]},
      "edge1": [0, 20, 0], "edge2": [20, 0, 0]})"));
  return doc;
}

json moving_room();

Scene load(const json& doc, double frame = 1) {
  return build_scene(parse_scene(doc, "motion.json", SceneLoadOptions{.frame = frame}));
}

TEST(MotionBlur, AMovingEdgeIsTheTimeAverageOfItsCoverage) {
  const Scene scene = load(moving_black_quad({0, 0.5}));
  ASSERT_TRUE(scene.motion_blur);
  std::string log;
  const int rejected = rejected_pixels(
      scene, 1.0,
      [](int i) {
        const auto [x0, x1] = pixel_span(i, 16, 4.0);
        return mean_left_fraction(x0, x1, -3.0, 0.0);  // white where left of the edge
      },
      log);
  EXPECT_EQ(rejected, 0) << log;
}

// Pixels whose means reject the edge swept from x = -3 to 0 over the shutter.
int rejected_against_the_sweep(const Scene& scene, std::string& log) {
  return rejected_pixels(
      scene, 1.0,
      [](int i) {
        const auto [x0, x1] = pixel_span(i, 16, 4.0);
        return mean_left_fraction(x0, x1, -3.0, 0.0);
      },
      log);
}

// The same edge from a deforming mesh: its quad moves as above while a
// triangle of the same mesh, behind the camera, is stretched another way.
// Not an affine motion: the mesh keeps vertex time steps, not an instance.
TEST(MotionBlur, ADeformingMeshBlursLikeTheMovingQuad) {
  json doc = moving_black_quad({0, 0.5});
  const auto positions_at = [](double e, double y) {
    return json{e, -10, 0, e + 20, -10, 0, e + 20, 10, 0, e, 10, 0, 0, 0, 50, 1, 0, 50, 0, y, 50};
  };
  doc["shapes"][0] = {
      {"type", "mesh"},
      {"material", "black"},
      {"indices", {0, 1, 2, 0, 2, 3, 4, 5, 6}},
      {"positions", {{"keys", {{1, positions_at(-3, 1)}, {2, positions_at(3, 2)}}}}}};
  const Scene scene = load(doc);
  ASSERT_EQ(scene.accel->geometry().meshes.size(), 1u);
  EXPECT_FALSE(rigid_motion(scene.accel->geometry().meshes[0]));
  std::string log;
  const int rejected = rejected_against_the_sweep(scene, log);
  EXPECT_EQ(rejected, 0) << log;
}

TEST(MotionBlur, KeyedCornersCentresAndTransformsMoveByInstance) {
  json doc = moving_room();
  doc["shapes"].push_back(json::parse(R"({"type": "mesh", "material": "white",
      "positions": [0, 0, 0, 0.2, 0, 0, 0, 0.2, 0, 0, 0, 0.2], "indices": [0, 1, 2, 0, 1, 3, 0, 2, 3],
      "transform": {"translate": {"keys": [[1, [0, 0.5, 0]], [2, [0.2, 0.6, 0]]]},
                    "rotate": {"axis": [0, 1, 0], "angle": {"keys": [[1, 0], [2, 90]]}}}})"));
  const Scene scene = load(doc);
  const AccelGeometry& g = scene.accel->geometry();
  ASSERT_EQ(g.spheres.size(), 1u);
  EXPECT_TRUE(rigid_motion(g.spheres[0]));
  ASSERT_EQ(g.meshes.size(), 1u);
  EXPECT_EQ(g.meshes[0].steps.size(), 9u);  // a rotation: the cap
  EXPECT_TRUE(rigid_motion(g.meshes[0]));
  EXPECT_FALSE(rigid_motion(g.quads[0]));  // still
}

// The camera moving instead: a still edge at x = 0 seen from a camera
// sliding from x = 3 to 0 over the shutter (looking straight down -z) is the
// edge at x = -3 .. 0 relative to it: the same expected pixels.
TEST(MotionBlur, AMovingCameraBlursLikeAMovingEdge) {
  json doc = moving_black_quad({0, 0.5});
  doc["shapes"][0]["corner"] = {0, -10, 0};
  doc["camera"]["from"] = json::parse(R"({"keys": [[1, [3, 0, 4]], [2, [-3, 0, 4]]]})");
  doc["camera"]["to"] = json::parse(R"({"keys": [[1, [3, 0, 0]], [2, [-3, 0, 0]]]})");
  const Scene scene = load(doc);
  ASSERT_EQ(scene.camera_steps.size(), 2u);
  std::string log;
  const int rejected = rejected_against_the_sweep(scene, log);
  EXPECT_EQ(rejected, 0) << log;
}

TEST(MotionBlur, TheEdgeTestRejectsAWrongTime) {
  // Every sample at the shutter's opening (a zero-length shutter at 0): the
  // image of the edge at -3, not the blur; the test above must see it.
  const Scene scene = load(moving_black_quad({0, 0}));
  ASSERT_FALSE(scene.motion_blur);
  std::string log;
  const int rejected = rejected_against_the_sweep(scene, log);
  EXPECT_GE(rejected, 4) << log;
}

// A white floor (z = 0) lit by a delta sun from (1, 0, 1), under a black
// blocker in the plane z = 1 covering x >= e(t), e keyed from -1 at frame 1
// to 5 at frame 2 (so [-1, 2] over the shutter). At one instant the floor
// point x is lit iff x + 1 <= e(t) (its shadow ray crosses z = 1 at x + 1;
// the camera ray, at 0.75 x, is then clear of the blocker too): the pixel is
// the time average of a lit fraction only if the shadow ray lives at the
// camera ray's time.
TEST(MotionBlur, ShadowRaysLiveAtTheCameraRaysTime) {
  json doc = edge_scene();
  doc["lights"] = json::parse(
      R"([{"type": "sun", "direction": [1, 0, 1], "irradiance": [2, 2, 2], "angle": 0}])");
  doc["shapes"].push_back(json::parse(R"({"type": "quad", "material": "white",
      "corner": [-20, -20, 0], "edge1": [40, 0, 0], "edge2": [0, 40, 0]})"));
  doc["shapes"].push_back(json::parse(R"({"type": "quad", "material": "black",
      "corner": {"keys": [[1, [-1, -10, 1]], [2, [5, -10, 1]]]},
      "edge1": [0, 20, 0], "edge2": [20, 0, 0]})"));
  const Scene scene = load(doc);
  // Lambertian: albedo / pi * irradiance * cos 45 degrees.
  const double lit = 0.5 / M_PI * 2.0 * std::sqrt(0.5);
  std::string log;
  const int rejected = rejected_pixels(
      scene, lit,
      [](int i) {
        const auto [x0, x1] = pixel_span(i, 16, 4.0);
        return mean_left_fraction(x0, x1, -1.0 - 1.0, 2.0 - 1.0);
      },
      log);
  EXPECT_EQ(rejected, 0) << log;
}

// An absorbing slab (sigma_a 10, 0.1 thick: z in [-0.1, 0]) in front of a
// white environment, its box keyed like the black quad's edge: x >= e(t),
// e sweeping [-3, 0] over the shutter. A pixel's mean is the transmittance
// exp(-sigma * length inside the box) averaged over the pixel and the
// shutter, by midpoint quadrature of the exact ray-box lengths.
json moving_slab(const json& shutter) {
  json doc = edge_scene();
  doc["render"]["shutter"] = shutter;
  doc["lights"] = json::parse(R"([{"type": "environment", "radiance": [1, 1, 1]}])");
  doc["media"] = json::parse(R"({"slab": {"type": "homogeneous", "sigma_a": [10, 10, 10],
      "sigma_s": [0, 0, 0], "bounds": {
        "min": {"keys": [[1, [-3, -10, -0.1]], [2, [3, -10, -0.1]]]},
        "max": {"keys": [[1, [17, 10, 0]], [2, [23, 10, 0]]]}}}})");
  return doc;
}

// Length of the ray o + t d (t >= 0) inside the box [lo, hi].
double length_in_box(const Vec3d& o, const Vec3d& d, const Vec3d& lo, const Vec3d& hi) {
  double a = 0, b = 1e30;
  for (int i = 0; i < 3; ++i) {
    double t0 = (lo[i] - o[i]) / d[i], t1 = (hi[i] - o[i]) / d[i];
    if (t0 > t1) std::swap(t0, t1);
    a = std::max(a, t0);
    b = std::min(b, t1);
  }
  return b > a ? (b - a) * length(d) : 0.0;
}

double slab_transmittance(int column, double ea, double eb) {
  const double tan_half_y = std::tan(15.0 * M_PI / 180.0), tan_half_x = tan_half_y * 8;
  constexpr int kX = 48, kY = 8, kT = 48;
  double sum = 0;
  for (int ix = 0; ix < kX; ++ix)
    for (int iy = 0; iy < kY; ++iy)
      for (int it = 0; it < kT; ++it) {
        const double fx = column + (ix + 0.5) / kX, fy = (iy + 0.5) / kY;  // row 0 (rows agree)
        const double e = ea + (eb - ea) * (it + 0.5) / kT;
        const Vec3d d{(2 * fx / 16 - 1) * tan_half_x, (1 - 2 * fy / 2) * tan_half_y, -1};
        sum += std::exp(-10 * length_in_box({0, 0, 4}, d, {e, -10, -0.1}, {e + 20, 10, 0}));
      }
  return sum / (kX * kY * kT);
}

TEST(MotionBlur, AMovingMediumIsTheTimeAverageOfItsTransmittance) {
  const Scene scene = load(moving_slab({0, 0.5}));
  ASSERT_TRUE(scene.motion_blur);
  std::string log;
  const int rejected = rejected_pixels(
      scene, 1.0, [](int i) { return slab_transmittance(i, -3, 0); }, log);
  EXPECT_EQ(rejected, 0) << log;
  // With every sample at the opening, the same test fails.
  EXPECT_GE(
      rejected_pixels(
          load(moving_slab({0, 0})), 1.0, [](int i) { return slab_transmittance(i, -3, 0); }, log),
      2);
}

// A room with a moving camera (smooth keys: 9 steps) and a moving sphere.
json moving_room() {
  return json::parse(R"({
    "format": "vesper-scene/1",
    "camera": {"type": "perspective", "to": [0, 1, 0], "up": [0, 1, 0], "fov": 40,
               "from": {"keys": [[1, [0, 1, 3.9]], [2, [0.3, 1.1, 3.8]]], "interp": "smooth"}},
    "film": {"width": 24, "height": 20},
    "render": {"spp": 8, "max_depth": 4, "seed": 3, "shutter": [-0.25, 0.25]},
    "materials": {"white": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
                  "red": {"type": "diffuse", "albedo": [0.6, 0.1, 0.1]}},
    "shapes": [
      {"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "material": "white"},
      {"type": "quad", "corner": [-1, 0, -1], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "white"},
      {"type": "sphere", "radius": 0.3, "material": "red",
       "center": {"keys": [[1, [-0.5, 0.3, 0]], [2, [0.5, 0.3, 0]]]}}
    ],
    "lights": [{"type": "quad", "corner": [-0.25, 1.98, -0.25], "edge1": [0.5, 0, 0],
                "edge2": [0, 0, 0.5], "radiance": [10, 10, 10]},
               {"type": "environment", "radiance": [0.1, 0.1, 0.1]}]
  })");
}

bool same_pixels(const LayeredImage& a, const LayeredImage& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

TEST(MotionBlur, AZeroLengthShutterIsTheStillFrameAtThatTime) {
  json instant = moving_room();
  instant["render"]["shutter"] = {0.3, 0.3};
  json still = moving_room();
  still["render"].erase("shutter");
  const Scene a = load(instant, 1), b = load(still, 1.3);
  EXPECT_FALSE(a.motion_blur);
  EXPECT_TRUE(same_pixels(render(a).image, render(b).image));
  // Not the frame itself (the test can fail).
  EXPECT_FALSE(same_pixels(render(a).image, render(load(still, 1)).image));
}

TEST(MotionBlur, AShutterOverAStillSceneChangesNothing) {
  json doc = moving_room();
  doc["camera"]["from"] = {0, 1, 3.9};
  doc["shapes"][2]["center"] = {0, 0.3, 0};
  const Scene with = load(doc);
  doc["render"].erase("shutter");
  const Scene without = load(doc);
  EXPECT_FALSE(with.motion_blur);
  EXPECT_TRUE(same_pixels(render(with).image, render(without).image));
}

TEST(MotionBlur, KeysHeldOverTheShutterMoveNothing) {
  // The sphere's keys end at frame 1.1, before the shutter [0, 0.4] of frame
  // 1.2 (the camera's run to frame 2): the sphere is still, the camera is not.
  json doc = moving_room();
  doc["render"]["shutter"] = {0, 0.4};
  doc["shapes"][2]["center"]["keys"] = json::parse("[[1, [-0.5, 0.3, 0]], [1.1, [0.2, 0.3, 0]]]");
  const SceneDescription d = parse_scene(doc, "m.json", SceneLoadOptions{.frame = 1.2});
  EXPECT_TRUE(d.shapes[2].steps.empty());
  EXPECT_DOUBLE_EQ(std::get<SphereShapeDesc>(d.shapes[2].geometry).center.x, 0.2);
  EXPECT_EQ(d.camera_steps.size(), 9u);
  // Nothing moving at all: no motion blur, the image of the still frame.
  doc["camera"]["from"] = {0, 1, 3.9};
  const Scene held = load(doc, 1.2);
  EXPECT_FALSE(held.motion_blur);
  doc["render"].erase("shutter");
  EXPECT_TRUE(same_pixels(render(held).image, render(load(doc, 1.2)).image));
}

TEST(MotionBlur, BitwiseIdenticalForOneAndTwoThreads) {
  const Scene scene = load(moving_room());
  ASSERT_TRUE(scene.motion_blur);
  EXPECT_EQ(scene.camera_steps.size(), 9u);  // smooth keys
  RenderOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const RenderResult a = render(scene, one);
  EXPECT_TRUE(same_pixels(a.image, render(scene, two).image));
  EXPECT_EQ(a.image.metadata.at("vesper:shutter"), "-0.25 0.25");
  EXPECT_EQ(a.image.metadata.at("vesper:motion_steps"), "9");
}

TEST(MotionBlur, SampleRangesMergeBitwiseToTheFullRender) {
  test::expect_ranges_merge_bitwise(load(moving_room()), RenderOptions{}, 3);
}

TEST(MotionBlur, StepsFollowTheKeys) {
  // Linear keys outside the shutter: 2 steps; a key inside it: the cap.
  json doc = moving_black_quad({0, 0.5});
  SceneDescription d = parse_scene(doc, "m.json", SceneLoadOptions{.frame = 1});
  ASSERT_EQ(d.motion_times.size(), 2u);
  EXPECT_DOUBLE_EQ(d.motion_times[1], 1.5);
  const auto& q = std::get<QuadShapeDesc>(d.shapes[0].steps[1]);
  EXPECT_DOUBLE_EQ(q.corner.x, 0.0);
  EXPECT_TRUE(d.camera_steps.empty());
  doc["shapes"][0]["corner"]["keys"] =
      json::parse("[[1, [-3, -10, 0]], [1.25, [0, -10, 0]], [2, [3, -10, 0]]]");
  EXPECT_EQ(parse_scene(doc, "m.json", SceneLoadOptions{.frame = 1}).motion_times.size(), 9u);
}

TEST(MotionBlur, TheHashCoversTheMotion) {
  // Two scenes alike at frame 1 that move differently over the shutter.
  json a = moving_black_quad({0, 0.5}), b = a;
  b["shapes"][0]["corner"]["keys"] = json::parse("[[1, [-3, -10, 0]], [2, [5, -10, 0]]]");
  json still_a = a, still_b = b;
  still_a["render"].erase("shutter");
  still_b["render"].erase("shutter");
  auto hash = [](const json& doc) {
    return parse_scene(doc, "m.json", SceneLoadOptions{.frame = 1}).content_hash;
  };
  EXPECT_EQ(hash(still_a), hash(still_b));
  EXPECT_NE(hash(a), hash(b));
}

TEST(MotionBlur, ABadShutterIsRejectedWithItsPath) {
  for (const char* bad : {"[0.5, 0]", "[0]", "\"open\"", "[0, 1e999]"}) {
    json doc = edge_scene();
    try {
      doc["render"]["shutter"] = json::parse(bad);
    } catch (const json::exception&) {
      continue;  // 1e999 does not even parse as a number
    }
    try {
      parse_scene(doc, "m.json");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.json_path(), "/render/shutter") << bad << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace vesper
