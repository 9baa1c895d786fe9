#pragma once
// What every fuzz target (tests/fuzz/*_target.cpp) shares. A target is
// libFuzzer's entry point, LLVMFuzzerTestOneInput: it feeds one input to one
// parser and catches only that parser's documented error type. Anything else
// is a finding: a crash, an abort, a hang, another exception escaping, or a
// broken invariant (fuzz::finding). The same target runs under the project's
// own driver (driver/, CI) and under libFuzzer (-DVESPER_LIBFUZZER=ON).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace vesper::fuzz {

// A broken invariant that is not a crash (a NaN camera from an accepted
// scene): prints `what` and aborts, so both drivers report the input.
[[noreturn]] void finding(const std::string& what);

// The parser accepted the input; the driver reports how many were, and keeps
// them as starting points for further mutation.
void note_accepted();
long long accepted_count();

// A folder the inputs' relative paths resolve against, created once per
// process (removed at exit) with the files the seed corpus names: meshes,
// an environment image and a .vdb (scene_assets.cpp adds those), EXR frames,
// a LUT, an OCIO config, a scene and an out/ folder (empty placeholders:
// only the scene parser reads them).
const std::filesystem::path& sandbox();

// The input as text.
inline std::string text_of(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace vesper::fuzz
