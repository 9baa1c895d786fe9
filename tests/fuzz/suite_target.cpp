// Fuzz target: the regression suite parser (`vesper-suite/1`, as `vesper
// regress suite.json` reads it). The documented error is SuiteError. Scene
// paths resolve in the sandbox, which holds scene.json.
#include "jobs/frame_range.h"
#include "regress/suite.h"
#include "tests/fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vesper;
  static const std::filesystem::path file = fuzz::sandbox() / "suite.json";
  regress::Suite suite;
  try {
    suite = regress::parse_suite_text(fuzz::text_of(data, size), file);
  } catch (const regress::SuiteError&) {
    return 0;
  }
  fuzz::note_accepted();
  // The suite checked every frame list; `vesper regress` parses them again.
  for (const regress::SuiteScene& s : suite.scenes) {
    try {
      parse_frame_range(s.frames);
    } catch (const FrameRangeError& e) {
      fuzz::finding(std::string("an accepted suite has a bad frame list: ") + e.what());
    }
  }
  return 0;
}
