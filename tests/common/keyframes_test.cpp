// Keyframed values: linear and smooth interpolation against hand values, the
// held ends, C1 continuity of "smooth", and errors that name the JSON path.
#include "common/keyframes.h"

#include <gtest/gtest.h>

#include <string>

#include "common/json_error.h"

namespace vesper {
namespace {

using nlohmann::json;

double at(const json& node, double t) {
  return keyframed_value(node, t, "s.json", "/v").get<double>();
}

std::string error_of(const json& node) {
  try {
    evaluate_keyframes(json{{"camera", {{"fov", node}}}}, 1, "scene.json");
  } catch (const JsonError& e) {
    return e.what();
  }
  return "(no JsonError)";
}

TEST(Keyframes, LinearMatchesHandValuesAndHoldsTheEnds) {
  const json k = json::parse(R"({"keys": [[1, 0], [3, 10], [4, 4]]})");
  EXPECT_DOUBLE_EQ(at(k, 2), 5);
  EXPECT_DOUBLE_EQ(at(k, 3.5), 7);
  EXPECT_DOUBLE_EQ(at(k, 3), 10);
  EXPECT_DOUBLE_EQ(at(k, -100), 0);
  EXPECT_DOUBLE_EQ(at(k, 1), 0);
  EXPECT_DOUBLE_EQ(at(k, 4), 4);
  EXPECT_DOUBLE_EQ(at(k, 1e9), 4);
}

TEST(Keyframes, VectorsInterpolatePerComponent) {
  const json k = json::parse(R"({"keys": [[0, [0, 2, -4]], [2, [4, 2, 0]]], "interp": "linear"})");
  EXPECT_EQ(keyframed_value(k, 0.5, "s.json", "/v"), json::parse("[1, 2, -3]"));
}

TEST(Keyframes, OneKeyIsAConstant) {
  const json k = json::parse(R"({"keys": [[5, 7]], "interp": "smooth"})");
  EXPECT_DOUBLE_EQ(at(k, -1), 7);
  EXPECT_DOUBLE_EQ(at(k, 5), 7);
  EXPECT_DOUBLE_EQ(at(k, 9), 7);
}

TEST(Keyframes, SmoothMatchesTheCatmullRomHermiteByHand) {
  // Tangents: 0 at frame 0 (an end), (3 - 0) / (3 - 0) = 1 at frame 1.
  // At s = 1/2 the Hermite basis is h00 = h01 = 1/2, h10 = 1/8, h11 = -1/8:
  // 0/2 + 0 + 1/2 - 1/8 = 0.375.
  const json k = json::parse(R"({"keys": [[0, 0], [1, 1], [3, 3]], "interp": "smooth"})");
  EXPECT_DOUBLE_EQ(at(k, 0.5), 0.375);
  EXPECT_DOUBLE_EQ(at(k, 0), 0);
  EXPECT_DOUBLE_EQ(at(k, 1), 1);
  EXPECT_DOUBLE_EQ(at(k, 3), 3);
}

TEST(Keyframes, SmoothIsC1AtInnerKeysAndAtTheHeldEnds) {
  const json k =
      json::parse(R"({"keys": [[0, 0], [1, 2], [2.5, -1], [4, 5]], "interp": "smooth"})");
  const double h = 1e-6;
  for (double t : {0.0, 1.0, 2.5, 4.0}) {
    const double left = (at(k, t) - at(k, t - h)) / h;
    const double right = (at(k, t + h) - at(k, t)) / h;
    EXPECT_NEAR(left, right, 1e-4) << "frame " << t;
  }
  // The slopes at the inner keys are Catmull-Rom's, 0 at the ends.
  EXPECT_NEAR((at(k, 1 + h) - at(k, 1 - h)) / (2 * h), (-1.0 - 0.0) / 2.5, 1e-5);
  EXPECT_NEAR((at(k, h) - at(k, 0)) / h, 0, 1e-4);
  // Linear is not C1 at an inner key: the check above can fail.
  json linear = k;
  linear["interp"] = "linear";
  EXPECT_GT(
      std::abs((at(linear, 1 + h) - at(linear, 1)) / h - (at(linear, 1) - at(linear, 1 - h)) / h),
      1);
}

TEST(Keyframes, EvaluationReplacesEveryKeyframeObjectAndLeavesTheRest) {
  const json doc = json::parse(R"({
    "format": "vesper-scene/1",
    "camera": {"from": {"keys": [[1, [0, 0, 0]], [3, [2, 0, 0]]]}, "fov": 40},
    "lights": [{"type": "point", "intensity": {"keys": [[1, 1], [2, 3]]}}]
  })");
  EXPECT_TRUE(has_keyframes(doc));
  const json at2 = evaluate_keyframes(doc, 2, "scene.json");
  EXPECT_FALSE(has_keyframes(at2));
  EXPECT_EQ(at2["camera"]["from"], json::parse("[1, 0, 0]"));
  EXPECT_EQ(at2["lights"][0]["intensity"], 3);
  EXPECT_EQ(at2["camera"]["fov"], 40);
  EXPECT_EQ(at2["format"], "vesper-scene/1");

  const json still = json::parse(R"({"camera": {"fov": 40}, "shapes": [{"type": "sphere"}]})");
  EXPECT_FALSE(has_keyframes(still));
  EXPECT_EQ(evaluate_keyframes(still, 9, "scene.json"), still);
}

TEST(Keyframes, MalformedKeysAreErrorsNamingTheFileAndPath) {
  EXPECT_EQ(error_of(json::parse(R"({"keys": []})")),
            "scene.json: /camera/fov/keys: expected at least one key [frame, value], got an "
            "empty array");
  EXPECT_NE(error_of(json::parse(R"({"keys": [[2, 1], [1, 3]]})"))
                .find("scene.json: /camera/fov/keys/1/0: expected frames in increasing order"),
            std::string::npos);
  EXPECT_NE(error_of(json::parse(R"({"keys": [[1, 1], [2, [1, 2]]]})"))
                .find("/camera/fov/keys/1/1: expected a value of the first key's shape"),
            std::string::npos);
  EXPECT_NE(error_of(json::parse(R"({"keys": [[1, [1, 2]], [2, [1, 2, 3]]]})"))
                .find("/camera/fov/keys/1/1: expected a value of the first key's shape"),
            std::string::npos);
  EXPECT_NE(error_of(json::parse(R"({"keys": [[1, "a"]]})"))
                .find("/camera/fov/keys/0/1: expected a number or an array of numbers"),
            std::string::npos);
  EXPECT_NE(error_of(json::parse(R"({"keys": [[1]]})")).find("/camera/fov/keys/0: expected a key"),
            std::string::npos);
  EXPECT_NE(
      error_of(json::parse(R"({"keys": [[1, 1]], "interp": "cubic"})")).find("/camera/fov/interp"),
      std::string::npos);
  EXPECT_NE(error_of(json::parse(R"({"keys": [[1, 1]], "interpolation": "linear"})"))
                .find("interpolation"),
            std::string::npos);
  EXPECT_NE(error_of(json::parse(R"({"keys": [[0, -1e308], [2, 1e308]]})"))
                .find("/camera/fov: expected keys whose interpolation stays within the double"),
            std::string::npos);
}

}  // namespace
}  // namespace vesper
