#include "regress/report_json.h"

#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/json_parse.h"
#include "common/json_reader.h"

namespace vesper::regress {

// Regions are plain figures: written by nlohmann's field list (its NaN/Inf
// dump as null), read back by read_region with JSON-path errors.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Region, x, y, width, height, z, p_value, golden_mean, new_mean,
                                   relative_change);

namespace {

using nlohmann::json;

// Non-finite numbers have no JSON form: they are written as null and read back as NaN.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json layer_json(const LayerResult& l) {
  json at = json::array();
  for (const Pixel& p : l.introduced_nonfinite_at) at.push_back({p.x, p.y});
  json worst = json::array(), z = json::array();
  for (const Region& r : l.worst) worst.push_back(r);
  for (float v : l.tile_z) z.push_back(number(v));
  return {{"layer", l.layer},
          {"verdict", verdict_name(l.verdict)},
          {"reasons", l.reasons},
          {"has_variance", l.has_variance},
          {"tiles", l.tiles},
          {"significant_tiles", l.significant_tiles},
          {"max_abs_z", number(l.max_abs_z)},
          {"min_detectable_change", number(l.min_detectable_change)},
          {"frame_detectable_change", number(l.frame_detectable_change)},
          {"histogram_distance", number(l.histogram_distance)},
          {"histogram_noise", number(l.histogram_noise)},
          {"nonfinite",
           {{"golden", l.golden_nonfinite},
            {"new", l.new_nonfinite},
            {"introduced", l.introduced_nonfinite},
            {"introduced_at", at}}},
          {"worst", worst},
          {"significance",
           {{"tile_size", l.tile_size},
            {"tiles_x", l.tiles_x},
            {"tiles_y", l.tiles_y},
            {"z", z},
            {"significant", l.tile_significant}}}};
}

json scene_json(const SceneResult& s) {
  json layers = json::array();
  for (const LayerResult& l : s.layers) layers.push_back(layer_json(l));
  return {{"name", s.name},
          {"verdict", verdict_name(s.verdict)},
          {"reasons", s.reasons},
          {"channels_added", s.channels_added},
          {"channels_missing", s.channels_missing},
          {"golden_seconds", number(s.golden_seconds)},
          {"new_seconds", number(s.new_seconds)},
          {"new_seconds_repeats", s.new_seconds_repeats},
          {"reused", s.reused},
          {"golden_image", s.golden_image},
          {"new_image", s.new_image},
          {"layers", layers}};
}

// ---- reading

double read_number(JsonReader& node, std::string_view key) {
  JsonReader c = node.child(key);
  return c.json().is_null() ? std::numeric_limits<double>::quiet_NaN() : c.as_number();
}

int read_int(JsonReader& node, std::string_view key) {
  return int(node.integer(key, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}

Verdict read_verdict(JsonReader& node) {
  static constexpr std::string_view kNames[] = {"pass", "regressed", "error"};
  return static_cast<Verdict>(node.enumeration("verdict", kNames));
}

std::vector<std::string> read_strings(JsonReader& node, std::string_view key) {
  const JsonReader a = node.array(key);
  std::vector<std::string> out;
  for (size_t i = 0; i < a.size(); ++i) out.push_back(a.element(i).as_string(true));
  return out;
}

// The array at `key`, each element read by `read`.
template <typename Read>
auto read_list(JsonReader& node, std::string_view key, Read read) {
  const JsonReader a = node.array(key);
  std::vector<decltype(read(a.element(0)))> out;
  for (size_t i = 0; i < a.size(); ++i) out.push_back(read(a.element(i)));
  return out;
}

// What every scene and layer says: its verdict and why.
void read_judgement(JsonReader& n, Verdict& verdict, std::vector<std::string>& reasons) {
  verdict = read_verdict(n);
  reasons = read_strings(n, "reasons");
}

Region read_region(JsonReader n) {
  n.expect_object();
  return {read_int(n, "x"),
          read_int(n, "y"),
          read_int(n, "width"),
          read_int(n, "height"),
          read_number(n, "z"),
          read_number(n, "p_value"),
          read_number(n, "golden_mean"),
          read_number(n, "new_mean"),
          read_number(n, "relative_change")};
}

void read_nonfinite(JsonReader n, LayerResult& l) {
  n.expect_object();
  l.golden_nonfinite = n.child("golden").as_uint64();
  l.new_nonfinite = n.child("new").as_uint64();
  l.introduced_nonfinite = n.child("introduced").as_uint64();
  const JsonReader at = n.array("introduced_at");
  for (size_t i = 0; i < at.size(); ++i) {
    const std::vector<double> xy = at.element(i).as_number_array();
    if (xy.size() != 2) at.element(i).fail("expected [x, y]");
    l.introduced_nonfinite_at.push_back({int(xy[0]), int(xy[1])});
  }
}

void read_significance(JsonReader n, LayerResult& l) {
  n.expect_object();
  l.tile_size = read_int(n, "tile_size");
  l.tiles_x = read_int(n, "tiles_x");
  l.tiles_y = read_int(n, "tiles_y");
  const JsonReader z = n.array("z");
  for (size_t i = 0; i < z.size(); ++i) {
    const JsonReader e = z.element(i);
    l.tile_z.push_back(e.json().is_null() ? std::numeric_limits<float>::quiet_NaN()
                                          : float(e.as_number()));
  }
  for (double v : n.array("significant").as_number_array(Range::closed(0, 1)))
    l.tile_significant.push_back(uint8_t(v));
}

LayerResult read_layer(JsonReader n) {
  n.expect_object();
  LayerResult l;
  l.layer = n.string("layer");
  read_judgement(n, l.verdict, l.reasons);
  l.has_variance = n.boolean("has_variance", false);
  l.tiles = read_int(n, "tiles");
  l.significant_tiles = read_int(n, "significant_tiles");
  l.max_abs_z = read_number(n, "max_abs_z");
  l.min_detectable_change = read_number(n, "min_detectable_change");
  l.frame_detectable_change = read_number(n, "frame_detectable_change");
  l.histogram_distance = read_number(n, "histogram_distance");
  l.histogram_noise = read_number(n, "histogram_noise");
  read_nonfinite(n.object("nonfinite"), l);
  l.worst = read_list(n, "worst", read_region);
  read_significance(n.object("significance"), l);
  return l;
}

SceneResult read_scene(JsonReader n) {
  n.expect_object();
  SceneResult s;
  s.name = n.string("name");
  read_judgement(n, s.verdict, s.reasons);
  s.channels_added = read_strings(n, "channels_added");
  s.channels_missing = read_strings(n, "channels_missing");
  s.golden_seconds = read_number(n, "golden_seconds");
  s.new_seconds = read_number(n, "new_seconds");
  s.new_seconds_repeats = n.array("new_seconds_repeats").as_number_array();
  s.reused = n.boolean("reused", false);
  s.golden_image = n.child("golden_image").as_string(true);
  s.new_image = n.child("new_image").as_string(true);
  s.layers = read_list(n, "layers", read_layer);
  return s;
}

}  // namespace

json report_to_json(const RunResult& run) {
  json scenes = json::array();
  for (const SceneResult& s : run.scenes) scenes.push_back(scene_json(s));
  return {{"format", kReportFormat},
          {"suite", run.suite},
          {"started_at", run.started_at},
          {"renderer_version", run.renderer_version},
          {"server", run.server},
          {"render_time_note", run.render_time_note},
          {"verdict", verdict_name(run.verdict)},
          {"scenes", scenes}};
}

RunResult report_from_json(const json& doc, const std::string& file) {
  JsonReader root(doc, file, "");
  root.expect_object();
  root.child("format").expect_string(kReportFormat);
  RunResult run;
  run.suite = root.child("suite").as_string(true);
  run.started_at = root.child("started_at").as_string(true);
  run.renderer_version = root.child("renderer_version").as_string(true);
  // Added within /1: reports written before them have neither.
  if (const auto v = root.optional_child("server")) run.server = v->as_string(true);
  if (const auto v = root.optional_child("render_time_note"))
    run.render_time_note = v->as_string(true);
  run.verdict = read_verdict(root);
  run.scenes = read_list(root, "scenes", read_scene);
  return run;
}

void write_report_json(const RunResult& run, const std::filesystem::path& path) {
  write_file_atomically(path, report_to_json(run).dump(2) + "\n");
}

RunResult read_report_json(const std::filesystem::path& path) {
  return report_from_json(read_json_file(path, "the report"), path.string());
}

}  // namespace vesper::regress
