#include <nlohmann/json.hpp>

#include "protocol/job_messages.h"
#include "server/api_error.h"
#include "server/blob_store.h"
#include "server/handlers.h"

namespace vesper {
namespace {

ApiResponse put(BlobStore& blobs, const ApiRequest& req) {
  const std::string& hash = req.params.at(0);
  const bool created = blobs.put(hash, req.body);
  return json_response(created ? 201 : 200, protocol::BlobStored{hash, int64_t(req.body.size())});
}

ApiResponse get(const BlobStore& blobs, const ApiRequest& req) {
  const std::string& hash = req.params.at(0);
  // A client asks before it uploads, and submits without uploading what the
  // server has: that blob is pending for it like an upload (garbage collection).
  if (req.head) blobs.mark_pending(hash);
  const auto file = blobs.file(hash);
  const auto size = blobs.size(hash);
  if (!file || !size) throw ApiError(404, "no blob " + hash);
  return file_response(*file, *size, "application/octet-stream");
}

}  // namespace

void add_blob_handlers(HandlerTable& table, BlobStore& blobs) {
  table[protocol::Endpoint::PutBlob] = [&blobs](const ApiRequest& r) { return put(blobs, r); };
  table[protocol::Endpoint::GetBlob] = [&blobs](const ApiRequest& r) { return get(blobs, r); };
}

}  // namespace vesper
