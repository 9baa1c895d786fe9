// load_suite: a valid suite resolves paths and merges thresholds; each kind
// of mistake is rejected naming the file, the JSON path and the reason.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "regress/suite.h"
#include "regress_dir_test.h"

namespace vesper::regress {
namespace {

namespace fs = std::filesystem;

class SuiteTest : public test::RegressDirTest {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "cornell");
    std::ofstream(dir_ / "cornell" / "scene.json") << "{}";
    std::ofstream(dir_ / "fog.json") << "{}";
  }

  fs::path write(const std::string& text) {
    const fs::path p = dir_ / "suite.json";
    std::ofstream(p) << text;
    return p;
  }
  // The error load_suite throws for a suite whose only scene is `scene`.
  SuiteError error_for_scene(const std::string& scene) {
    return error_for(R"({"format": "vesper-suite/1", "scenes": [)" + scene + "]}");
  }
  SuiteError error_for(const std::string& text) {
    const fs::path p = write(text);
    try {
      load_suite(p);
    } catch (const SuiteError& e) {
      EXPECT_EQ(e.file(), p.string());
      return e;
    }
    ADD_FAILURE() << "accepted: " << text;
    return SuiteError("", "", "");
  }
};

TEST_F(SuiteTest, LoadsScenesResolvesPathsAndMergesThresholds) {
  const fs::path p = write(R"({
    "format": "vesper-suite/1",
    "thresholds": {"alpha": 0.001, "tile_size": 32},
    "scenes": [
      {"name": "cornell", "scene": "cornell/scene.json", "spp": 64, "frames": "1-3",
       "layers": ["beauty", "fog"], "thresholds": {"tile_size": 8, "min_relative_change": 0.01}},
      {"name": "fog.v2", "scene": "./fog.json", "noise_target": 0.05}
    ]})");
  const Suite s = load_suite(p);
  EXPECT_EQ(s.path, p);
  ASSERT_EQ(s.scenes.size(), 2u);
  const SuiteScene& c = s.scenes[0];
  EXPECT_EQ(c.name, "cornell");
  EXPECT_EQ(c.scene, fs::absolute(dir_ / "cornell" / "scene.json").lexically_normal());
  EXPECT_EQ(c.spp, 64);
  EXPECT_FALSE(c.noise_target);
  EXPECT_EQ(c.frames, "1-3");
  EXPECT_EQ(c.layers, (std::vector<std::string>{"beauty", "fog"}));
  EXPECT_EQ(c.thresholds.alpha, 0.001);  // the suite's
  EXPECT_EQ(c.thresholds.tile_size, 8);  // the scene's own
  EXPECT_EQ(c.thresholds.min_relative_change, 0.01);
  EXPECT_EQ(c.thresholds.max_slowdown, Thresholds{}.max_slowdown);  // the default
  const SuiteScene& f = s.scenes[1];
  EXPECT_EQ(f.scene, fs::absolute(dir_ / "fog.json").lexically_normal());
  EXPECT_FALSE(f.spp);
  EXPECT_EQ(f.noise_target, 0.05);
  EXPECT_EQ(f.frames, "1");
  EXPECT_FALSE(f.layers);
  EXPECT_EQ(f.thresholds.tile_size, 32);
}

// A rejected document: the JSON path named and a part of the message.
struct Rejected {
  const char* text;
  const char* json_path;
  const char* reason;
};

void expect_names(const SuiteError& e, const Rejected& c) {
  EXPECT_EQ(e.json_path(), c.json_path) << c.text << "\n" << e.what();
  EXPECT_NE(e.message().find(c.reason), std::string::npos) << c.text << "\n" << e.what();
}

TEST_F(SuiteTest, RejectsBadScenesNamingThePathAndTheReason) {
  const Rejected cases[] = {
      // each text is the suite's only scene
      {R"({"name": "a/b", "scene": "fog.json", "spp": 4})", "/scenes/0/name", "letters, digits"},
      {R"({"name": "..", "scene": "fog.json", "spp": 4})", "/scenes/0/name", "not \".\""},
      {R"({"name": "c", "scene": "nope.json", "spp": 4})", "/scenes/0/scene", "no scene file"},
      {R"({"name": "c", "spp": 4})", "/scenes/0", "scene"},
      {R"({"scene": "fog.json", "spp": 4})", "/scenes/0", "name"},
      {R"({"name": "c", "scene": "fog.json"})", "/scenes/0",
       "'spp' (samples per pixel) or 'noise_target'"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "noise_target": 0.1})", "/scenes/0",
       "not both"},
      {R"({"name": "c", "scene": "fog.json", "spp": 0})", "/scenes/0/spp", "integer"},
      {R"({"name": "c", "scene": "fog.json", "spp": 2.5})", "/scenes/0/spp", "integer"},
      {R"({"name": "c", "scene": "fog.json", "noise_target": -1})", "/scenes/0/noise_target",
       "positive"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "frames": "5-1"})", "/scenes/0/frames",
       "frame list"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "frames": 3})", "/scenes/0/frames",
       "string"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "layers": []})", "/scenes/0/layers",
       "at least one layer"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "layers": ["fog", "fog"]})",
       "/scenes/0/layers/1", "duplicate layer \"fog\" (already at /scenes/0/layers/0)"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "layers": [3]})", "/scenes/0/layers/0",
       "string"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "spp_": 4})", "/scenes/0/spp_",
       "did you mean 'spp'?"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "thresholds": {"alfa": 0.1}})",
       "/scenes/0/thresholds/alfa", "did you mean 'alpha'?"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "thresholds": {"alpha": 1.5}})",
       "/scenes/0/thresholds/alpha", "(0, 1)"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "thresholds": {"tile_size": 0}})",
       "/scenes/0/thresholds/tile_size", "integer"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "thresholds": {"max_slowdown": 0.9}})",
       "/scenes/0/thresholds/max_slowdown", "(1, "},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "thresholds": {"min_relative_change": -1}})",
       "/scenes/0/thresholds/min_relative_change", "non-negative"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "thresholds": {"max_histogram_distance": "x"}})",
       "/scenes/0/thresholds/max_histogram_distance", "number"},
      {R"({"name": "c", "scene": "fog.json", "spp": 4, "thresholds": []})", "/scenes/0/thresholds",
       "object"},
      {R"("cornell")", "/scenes/0", "object"},
  };
  for (const Rejected& c : cases) expect_names(error_for_scene(c.text), c);
}

TEST_F(SuiteTest, RejectsBadSuitesNamingThePathAndTheReason) {
  const Rejected cases[] = {
      {R"({"format": "vesper-suite/2", "scenes": []})", "/format", "vesper-suite/1"},
      {R"({"scenes": []})", "/", "format"},
      {R"({"format": "vesper-suite/1", "scene": []})", "/scene", "did you mean 'scenes'?"},
      {R"({"format": "vesper-suite/1", "scenes": []})", "/scenes", "at least one scene"},
      {R"({"format": "vesper-suite/1", "scenes": {}})", "/scenes", "array"},
      {R"({"format": "vesper-suite/1", "thresholds": {"tile_size": 99999}, "scenes": []})",
       "/thresholds/tile_size", "integer"},
      {R"({"format": "vesper-suite/1", "scenes": [
          {"name": "c", "scene": "fog.json", "spp": 4},
          {"name": "c", "scene": "cornell/scene.json", "spp": 4}]})",
       "/scenes/1/name", "duplicate scene name \"c\" (already at /scenes/0)"},
      {R"([1, 2])", "/", "object"},
  };
  for (const Rejected& c : cases) expect_names(error_for(c.text), c);
}

TEST_F(SuiteTest, InvalidJsonAndMissingFilesNameTheFile) {
  const SuiteError bad = error_for(R"({"format": "vesper-suite/1",)");
  EXPECT_NE(std::string(bad.what()).find("suite.json"), std::string::npos) << bad.what();
  EXPECT_NE(bad.message().find("line"), std::string::npos) << bad.what();
  try {
    load_suite(dir_ / "missing.json");
    ADD_FAILURE() << "a missing suite was accepted";
  } catch (const SuiteError& e) {
    EXPECT_EQ(e.file(), (dir_ / "missing.json").string());
    EXPECT_NE(e.message().find("cannot open"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesper::regress
