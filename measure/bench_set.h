#pragma once
// The benchmark set, `vesper-bench/1` (docs/bench.md): which scenes `vesper
// bench` measures, at what size, along which spp ladder and against which
// reference spp, with optional `quick` overrides for `--quick`.
// {"format": "vesper-bench/1", "quick": {...}, "scenes": [{"name": "cornell",
//  "path": "../scenes/cornell/scene.json", "kind": "surface", "width": 128,
//  "height": 128, "spp": [1, 2, 4, 8], "reference_spp": 2048}]}
// Paths are relative to the set's file.
#include <filesystem>
#include <string>
#include <vector>

#include "common/json_error.h"

namespace vesper::measure {

// What one scene is measured at (the full or the --quick settings).
struct BenchSettings {
  int width = 0, height = 0;
  std::vector<int> spp_ladder;  // strictly increasing
  int reference_spp = 0;        // even: the reference is two halves
};

struct BenchSetScene {
  std::string name;            // unique; [A-Za-z0-9_.-]+ (it names files)
  std::filesystem::path path;  // absolute, lexically normal
  std::string kind;            // "surface" or "volume"
  BenchSettings full, quick;   // quick = full with the set's and the scene's `quick` keys
};

struct BenchSet {
  std::filesystem::path path;
  std::vector<BenchSetScene> scenes;
};

// A rejected set: what() reads "<file>: <json path>: <message>".
class BenchSetError : public JsonError {
 public:
  using JsonError::JsonError;
};

// Reads and validates the whole file (unknown keys, types, ranges, duplicate
// names, a ladder that does not increase, an odd reference spp, a scene file
// that does not exist). A missing asset of an existing scene (the smoke VDB)
// is not an error here: the runner skips that scene with a note.
BenchSet load_bench_set(const std::filesystem::path& path);
BenchSet parse_bench_set_text(const std::string& text, const std::filesystem::path& path);

}  // namespace vesper::measure
