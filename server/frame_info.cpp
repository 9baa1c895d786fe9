#include "server/frame_info.h"

namespace vesper {

protocol::FrameInfo frame_info(const FrameStatus& f,
                               const std::map<int, std::string>& merge_failures) {
  protocol::FrameInfo out;
  out.frame = f.frame;
  out.tasks = f.tasks;
  out.done = f.done;
  if (!f.output.empty() || (f.complete() && f.tasks == 1)) {
    out.state = protocol::FrameState::Ready;
    out.blob = f.output.empty() ? f.results[0] : f.output;
    if (f.noise) {
      out.noise_reached = f.noise->noise_reached;
      out.spp_mean = f.noise->spp_mean;
      out.stop_reason = f.noise->stop_reason;
    }
  } else if (f.failed + f.canceled > 0) {
    out.state = protocol::FrameState::Failed;
    out.error =
        std::to_string(f.failed) + " task(s) failed, " + std::to_string(f.canceled) + " canceled";
  } else if (auto it = merge_failures.find(f.frame); f.complete() && it != merge_failures.end()) {
    out.state = protocol::FrameState::Failed;
    out.error = it->second;
  }
  return out;
}

}  // namespace vesper
