#pragma once
// The renders of `vesper regress --server`: the whole suite submitted to the
// farm as one batch (a job per suite scene with all its frames, rendered as
// --local renders them: the variance AOV, per-layer variance, the seed, the
// film scale), followed under one progress bar, and every frame's output
// (merged by the server) fetched. The farm reuses identical tasks (same
// scene, settings and renderer build): a frame whose every task took an
// earlier result was not rendered again, and says so.
#include <filesystem>
#include <optional>
#include <vector>

#include "cli/farm_client.h"
#include "cli/regress_render.h"

namespace vesper::cli {

struct FarmBatchSettings {
  std::filesystem::path out_dir;  // the frames are fetched here as <label>.exr
  std::optional<unsigned long long> seed;
  bool show_progress = true;
};

// One SuiteRender per element of `frames`, in order. A frame that was not
// rendered carries why: the failed task's log tail, a scene the farm refused,
// a canceled job. Throws FarmClientError only when the server does not
// answer at all before anything was submitted.
std::vector<SuiteRender> render_suite_on_farm(FarmClient& client, const regress::Suite& suite,
                                              const std::vector<SuiteFrame>& frames,
                                              const FarmBatchSettings& settings);

}  // namespace vesper::cli
