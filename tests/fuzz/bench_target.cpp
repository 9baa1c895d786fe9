// Fuzz target: the benchmark set parser (`vesper-bench/1`, as `vesper bench
// --scenes FILE` reads it). The documented error is BenchSetError. Scene
// paths resolve in the sandbox, which holds scene.json.
#include <string>

#include "measure/bench_set.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

// What the runner relies on in an accepted set.
void check_settings(const vesper::measure::BenchSettings& s) {
  using vesper::fuzz::finding;
  if (s.width < 1 || s.height < 1) finding("an accepted set has an empty film");
  if (s.spp_ladder.empty()) finding("an accepted set has an empty spp ladder");
  for (size_t i = 0; i < s.spp_ladder.size(); ++i)
    if (s.spp_ladder[i] < 1 || (i > 0 && s.spp_ladder[i] <= s.spp_ladder[i - 1]))
      finding("an accepted set has a ladder that does not increase from 1 up");
  if (s.reference_spp < 2 || s.reference_spp % 2 != 0)
    finding("an accepted set has a reference spp that is not even");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vesper;
  static const std::filesystem::path file = fuzz::sandbox() / "bench.json";
  measure::BenchSet set;
  try {
    set = measure::parse_bench_set_text(fuzz::text_of(data, size), file);
  } catch (const measure::BenchSetError&) {
    return 0;
  }
  fuzz::note_accepted();
  for (const measure::BenchSetScene& s : set.scenes) {
    check_settings(s.full);
    check_settings(s.quick);
    if (s.kind != "surface" && s.kind != "volume") fuzz::finding("an accepted set has a bad kind");
  }
  return 0;
}
