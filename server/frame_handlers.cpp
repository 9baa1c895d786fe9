#include "server/frame_handlers.h"

#include <nlohmann/json.hpp>

#include "protocol/job_messages.h"
#include "server/api_error.h"
#include "server/blob_store.h"
#include "server/frame_merger.h"
#include "server/locked_store.h"

namespace vesper {
namespace {

using protocol::FrameState;

protocol::FrameInfo frame_info(const FrameStatus& f, const std::map<int, std::string>& failures) {
  protocol::FrameInfo out{f.frame, FrameState::Pending, f.tasks, f.done, {}, {}};
  if (!f.output.empty() || (f.complete() && f.tasks == 1)) {
    out.state = FrameState::Ready;
    out.blob = f.output.empty() ? f.results[0] : f.output;
  } else if (f.failed + f.canceled > 0) {
    out.state = FrameState::Failed;
    out.error =
        std::to_string(f.failed) + " task(s) failed, " + std::to_string(f.canceled) + " canceled";
  } else if (auto it = failures.find(f.frame); f.complete() && it != failures.end()) {
    out.state = FrameState::Failed;
    out.error = it->second;
  }
  return out;
}

// The HTTP status of a frame that is not ready.
int status_of(FrameMerger::State s) {
  switch (s) {
    case FrameMerger::State::Pending:
    case FrameMerger::State::TasksFailed:
      return 409;
    case FrameMerger::State::Unavailable:
    case FrameMerger::State::Stopping:
      return 503;
    case FrameMerger::State::Ready:
    case FrameMerger::State::MergeFailed:
      break;
  }
  return 500;
}

}  // namespace

void FrameHandlers::add_to(HandlerTable& table) {
  table[protocol::Endpoint::ListFrames] = [this](const ApiRequest& r) { return list(r); };
  table[protocol::Endpoint::GetFrame] = [this](const ApiRequest& r) { return get(r); };
}

ApiResponse FrameHandlers::list(const ApiRequest& req) {
  const int64_t id = id_param(req, 0);
  const std::vector<FrameStatus> frames = store_.with([&](JobStore& s) {
    require_job(s, id);
    return s.frames(id);
  });
  const std::map<int, std::string> failures = merger_.failures(id);
  protocol::FrameList out;
  for (const FrameStatus& f : frames) out.frames.push_back(frame_info(f, failures));
  return json_response(200, out);
}

ApiResponse FrameHandlers::get(const ApiRequest& req) {
  const int64_t id = id_param(req, 0);
  const int frame = frame_param(req, 1);
  store_.with([&](JobStore& s) { require_job(s, id); });
  const auto out = merger_.output(id, frame, /*retry=*/true);
  if (!out) throw ApiError(404, "job " + std::to_string(id) + " has no frame " + req.params[1]);
  if (out->state != FrameMerger::State::Ready) throw ApiError(status_of(out->state), out->message);
  const auto file = blobs_.file(out->blob);
  const auto size = blobs_.size(out->blob);
  if (!file || !size)
    throw ApiError(500, "the output blob " + out->blob + " of " +
                            FrameMerger::frame_name(id, frame) + " is missing from the blob store");
  ApiResponse res = file_response(*file, *size, "image/x-exr");
  res.headers.emplace_back(std::string(protocol::kBlobHeader), out->blob);
  return res;
}

}  // namespace vesper
