#include "server/handlers.h"

#include <nlohmann/json.hpp>

#include "protocol/job_messages.h"
#include "server/api_error.h"
#include "server/blob_store.h"
#include "server/frame_info.h"
#include "server/frame_merger.h"
#include "server/frame_views.h"
#include "server/locked_store.h"

namespace vesper {
namespace {

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

ApiResponse list(const FrameHandlerDeps& d, const ApiRequest& req) {
  const int64_t id = id_param(req, 0);
  const std::vector<FrameStatus> frames = d.store.read([&](const JobStore& s) {
    require_job(s, id);
    return s.frames(id);
  });
  const std::map<int, std::string> failures = d.merger.failures(id);
  protocol::FrameList out;
  for (const FrameStatus& f : frames) out.frames.push_back(frame_info(f, failures));
  return json_response(200, out);
}

struct ReadyOutput {
  std::string blob;
  std::filesystem::path file;
  std::uintmax_t size = 0;
};

// The output of the request's frame (merged first if needed), or the
// ApiError that says why there is none yet.
ReadyOutput ready_output(const FrameHandlerDeps& d, const ApiRequest& req) {
  const int64_t id = id_param(req, 0);
  const int frame = frame_param(req, 1);
  d.store.read([&](const JobStore& s) { require_job(s, id); });
  const auto out = d.merger.output(id, frame, /*retry=*/true);
  if (!out) throw ApiError(404, "job " + std::to_string(id) + " has no frame " + req.params[1]);
  if (out->state != FrameMerger::State::Ready) throw ApiError(status_of(out->state), out->message);
  const auto file = d.blobs.file(out->blob);
  const auto size = d.blobs.size(out->blob);
  if (!file || !size)
    throw ApiError(500, "the output blob " + out->blob + " of " +
                            FrameMerger::frame_name(id, frame) + " is missing from the blob store");
  return {out->blob, *file, *size};
}

ApiResponse get(const FrameHandlerDeps& d, const ApiRequest& req) {
  const ReadyOutput out = ready_output(d, req);
  ApiResponse res = file_response(out.file, out.size, "image/x-exr");
  res.headers.emplace_back(std::string(protocol::kBlobHeader), out.blob);
  return res;
}

// A view of the frame (frame_views.h): made once per output blob, so the
// browser may keep it for a while.
template <class View>
ApiResponse view(const FrameHandlerDeps& d, const ApiRequest& req, View make,
                 const char* content_type) {
  const ReadyOutput out = ready_output(d, req);
  std::filesystem::path file;
  try {
    file = make(out);
  } catch (const CompError& e) {
    throw ApiError(500, "output blob " + out.blob + ": " + e.what());
  }
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec) throw ApiError(500, file.string() + ": " + ec.message());
  ApiResponse res = file_response(file, size, content_type);
  res.headers.emplace_back(std::string(protocol::kBlobHeader), out.blob);
  res.headers.emplace_back("Cache-Control", "private, max-age=3600");
  return res;
}

}  // namespace

void add_frame_handlers(HandlerTable& table, const FrameHandlerDeps& d) {
  table[protocol::Endpoint::ListFrames] = [d](const ApiRequest& r) { return list(d, r); };
  table[protocol::Endpoint::GetFrame] = [d](const ApiRequest& r) { return get(d, r); };
  table[protocol::Endpoint::FrameThumbnail] = [d](const ApiRequest& r) {
    return view(
        d, r, [&](const ReadyOutput& o) { return d.views.thumbnail(o.blob, o.file); }, "image/png");
  };
  table[protocol::Endpoint::FrameHistogram] = [d](const ApiRequest& r) {
    return view(
        d, r, [&](const ReadyOutput& o) { return d.views.histogram(o.blob, o.file); },
        "application/json");
  };
}

}  // namespace vesper
