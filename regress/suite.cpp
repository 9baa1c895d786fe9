// load_suite: `vesper-suite/1` (docs/regression.md), validated with the same
// reader as scenes, so every error names the file and the JSON path.
#include "regress/suite.h"

#include <algorithm>
#include <climits>
#include <system_error>

#include <nlohmann/json.hpp>

#include "common/json_parse.h"
#include "common/json_reader.h"
#include "common/named_items.h"
#include "jobs/frame_range.h"

namespace vesper::regress {
namespace {

constexpr std::string_view kFormat = "vesper-suite/1";

// Overrides the keys present in `node`; the others keep `base`'s values, so a
// scene's thresholds start from the suite's.
Thresholds parse_thresholds(JsonReader node, Thresholds t) {
  node.expect_object();
  node.allow_keys(
      {"alpha", "tile_size", "min_relative_change", "max_slowdown", "max_histogram_distance"});
  t.alpha = node.number("alpha", t.alpha, Range::open(0, 1));
  t.tile_size = int(node.integer("tile_size", t.tile_size, 1, 4096));
  t.min_relative_change =
      node.number("min_relative_change", t.min_relative_change, Range::non_negative());
  t.max_slowdown = node.number("max_slowdown", t.max_slowdown, Range::left_open(1, 1e6));
  t.max_histogram_distance =
      node.number("max_histogram_distance", t.max_histogram_distance, Range::non_negative());
  return t;
}

// Names become file names under --goldens and --report: no separators, no "." or "..".
std::string parse_name(JsonReader node) {
  const std::string name = node.string("name");
  const bool allowed = std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '.' || c == '-';
  });
  if (!allowed || name == "." || name == "..")
    node.fail_key("name",
                  "expected a name of letters, digits, '_', '.' and '-' (not \".\" or "
                  "\"..\": it names files), got \"" +
                      name + "\"");
  return name;
}

std::filesystem::path parse_scene_path(JsonReader& node, const std::filesystem::path& base) {
  const std::filesystem::path relative = node.string("scene");
  const std::filesystem::path file = (base / relative).lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    node.fail_key("scene", "no scene file " + file.string());
  return file;
}

void parse_budget(JsonReader& node, SuiteScene& scene) {
  const bool spp = node.has("spp"), noise = node.has("noise_target");
  if (spp == noise)
    node.fail(spp ? "expected either 'spp' or 'noise_target', not both"
                  : "expected 'spp' (samples per pixel) or 'noise_target' (relative error)");
  if (spp) scene.spp = int(node.integer("spp", 1, INT_MAX));
  if (noise) scene.noise_target = node.number("noise_target", Range::positive());
}

std::vector<std::string> parse_layers(JsonReader node) {
  node.expect_array();
  if (node.size() == 0) node.fail("expected at least one layer name (or leave 'layers' out)");
  std::vector<std::string> layers;
  for (size_t i = 0; i < node.size(); ++i) {
    const JsonReader e = node.element(i);
    const std::string name = e.as_string();
    const auto seen = std::find(layers.begin(), layers.end(), name);
    if (seen != layers.end())
      e.fail("duplicate layer \"" + name + "\" (already at " +
             json_pointer_append(node.path(), size_t(seen - layers.begin())) + ")");
    layers.push_back(name);
  }
  return layers;
}

SuiteScene parse_scene(JsonReader node, const std::filesystem::path& base,
                       const Thresholds& defaults) {
  node.expect_object();
  node.allow_keys(
      {"name", "scene", "spp", "noise_target", "frames", "layers", "scale", "thresholds"});
  SuiteScene scene;
  scene.name = parse_name(node);
  scene.scene = parse_scene_path(node, base);
  parse_budget(node, scene);
  if (const auto frames = node.optional_child("frames")) {
    scene.frames = frames->as_string();
    try {
      parse_frame_range(scene.frames);
    } catch (const FrameRangeError& e) {
      frames->fail(std::string("expected a frame list such as \"1\", \"1-10\" or \"1,5,9\": ") +
                   e.what());
    }
  }
  if (const auto layers = node.optional_child("layers")) scene.layers = parse_layers(*layers);
  if (node.has("scale")) scene.scale = node.number("scale", Range::left_open(0, 4));
  scene.thresholds = defaults;
  if (const auto t = node.optional_child("thresholds"))
    scene.thresholds = parse_thresholds(*t, defaults);
  return scene;
}

Suite parse_suite(const nlohmann::json& doc, const std::filesystem::path& file) {
  JsonReader root(doc, file.string(), "");
  root.expect_object();
  root.child("format").expect_string(kFormat);
  root.allow_keys({"format", "thresholds", "scenes"});
  Thresholds defaults;
  if (const auto t = root.optional_child("thresholds")) defaults = parse_thresholds(*t, defaults);
  const JsonReader scenes = root.array("scenes");
  Suite suite;
  suite.path = file;
  const std::filesystem::path base = std::filesystem::absolute(file).parent_path();
  suite.scenes = read_named_items<SuiteScene>(
      scenes, [&](const JsonReader& node) { return parse_scene(node, base, defaults); });
  return suite;
}

}  // namespace

Suite parse_suite_text(const std::string& text, const std::filesystem::path& path) {
  return rethrow_json_error_as<SuiteError>(
      [&] { return parse_suite(parse_json(text, path.string()), path); });
}

Suite load_suite(const std::filesystem::path& path) {
  return rethrow_json_error_as<SuiteError>(
      [&] { return parse_suite(read_json_file(path, "the suite file"), path); });
}

}  // namespace vesper::regress
