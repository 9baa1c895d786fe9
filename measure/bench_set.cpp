// load_bench_set: `vesper-bench/1` (docs/bench.md), validated with the
// project's JSON reader so every error names the file and the JSON path.
#include "measure/bench_set.h"

#include <algorithm>
#include <optional>
#include <system_error>

#include <nlohmann/json.hpp>

#include "common/json_parse.h"
#include "common/json_reader.h"
#include "common/named_items.h"

namespace vesper::measure {
namespace {

constexpr std::string_view kFormat = "vesper-bench/1";
constexpr int kMaxSide = 16384;
constexpr int kMaxSpp = 1 << 20;
const std::string_view kKinds[] = {"surface", "volume"};

// --quick without a `quick` object anywhere: runs in seconds.
BenchSettings builtin_quick() { return {32, 24, {1, 2, 4}, 16}; }

std::vector<int> parse_ladder(JsonReader node) {
  node.expect_array();
  if (node.size() == 0) node.fail("expected at least one spp, e.g. [1, 2, 4, 8]");
  std::vector<int> ladder;
  for (size_t i = 0; i < node.size(); ++i) {
    const JsonReader e = node.element(i);
    const int spp = int(e.as_integer(1, kMaxSpp));
    if (!ladder.empty() && spp <= ladder.back())
      e.fail("expected an spp greater than the previous one (" + std::to_string(ladder.back()) +
             "): the ladder increases");
    ladder.push_back(spp);
  }
  return ladder;
}

// Required without a fallback (a scene's own settings), optional in `quick`.
int parse_reference_spp(JsonReader& node, std::optional<int> fallback) {
  const int spp = fallback ? int(node.integer("reference_spp", *fallback, 2, kMaxSpp))
                           : int(node.integer("reference_spp", 2, kMaxSpp));
  if (spp % 2 != 0)
    node.fail_key("reference_spp",
                  "expected an even number: the reference is rendered as two halves, got " +
                      std::to_string(spp));
  return spp;
}

// Overrides the keys present in `node`; the others keep `base`'s values.
BenchSettings parse_settings(JsonReader& node, BenchSettings s, bool required) {
  if (required) {
    s.width = int(node.integer("width", 1, kMaxSide));
    s.height = int(node.integer("height", 1, kMaxSide));
    s.spp_ladder = parse_ladder(node.child("spp"));
    s.reference_spp = parse_reference_spp(node, std::nullopt);
    return s;
  }
  s.width = int(node.integer("width", s.width, 1, kMaxSide));
  s.height = int(node.integer("height", s.height, 1, kMaxSide));
  if (const auto ladder = node.optional_child("spp")) s.spp_ladder = parse_ladder(*ladder);
  s.reference_spp = parse_reference_spp(node, s.reference_spp);
  return s;
}

BenchSettings parse_quick(JsonReader node, const BenchSettings& base) {
  node.expect_object();
  node.allow_keys({"width", "height", "spp", "reference_spp"});
  return parse_settings(node, base, false);
}

// Names become file names in -o and in the reference cache.
std::string parse_name(JsonReader& node) {
  const std::string name = node.string("name");
  const bool allowed = std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '.' || c == '-';
  });
  if (!allowed || name == "." || name == "..")
    node.fail_key("name",
                  "expected a name of letters, digits, '_', '.' and '-' (it names files), "
                  "got \"" +
                      name + "\"");
  return name;
}

BenchSetScene parse_scene(JsonReader node, const std::filesystem::path& base,
                          const BenchSettings& quick_defaults) {
  node.expect_object();
  node.allow_keys({"name", "path", "kind", "width", "height", "spp", "reference_spp", "quick"});
  BenchSetScene scene;
  scene.name = parse_name(node);
  scene.path = (base / node.string("path")).lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(scene.path, ec))
    node.fail_key("path", "no scene file " + scene.path.string());
  scene.kind = std::string(kKinds[node.enumeration("kind", kKinds)]);
  scene.full = parse_settings(node, {}, true);
  scene.quick = quick_defaults;
  if (const auto q = node.optional_child("quick")) scene.quick = parse_quick(*q, quick_defaults);
  return scene;
}

BenchSet parse_set(const nlohmann::json& doc, const std::filesystem::path& file) {
  JsonReader root(doc, file.string(), "");
  root.expect_object();
  root.child("format").expect_string(kFormat);
  root.allow_keys({"format", "quick", "scenes"});
  BenchSettings quick = builtin_quick();
  if (const auto q = root.optional_child("quick")) quick = parse_quick(*q, quick);
  const JsonReader scenes = root.array("scenes");
  BenchSet set;
  set.path = file;
  const std::filesystem::path base = std::filesystem::absolute(file).parent_path();
  set.scenes = read_named_items<BenchSetScene>(
      scenes, [&](const JsonReader& node) { return parse_scene(node, base, quick); });
  return set;
}

}  // namespace

BenchSet parse_bench_set_text(const std::string& text, const std::filesystem::path& path) {
  return rethrow_json_error_as<BenchSetError>(
      [&] { return parse_set(parse_json(text, path.string()), path); });
}

BenchSet load_bench_set(const std::filesystem::path& path) {
  return rethrow_json_error_as<BenchSetError>(
      [&] { return parse_set(read_json_file(path, "the benchmark set"), path); });
}

}  // namespace vesper::measure
