#include "server/blob_handlers.h"

#include <nlohmann/json.hpp>

#include "protocol/job_messages.h"
#include "server/api_error.h"
#include "server/blob_store.h"

namespace vesper {

void BlobHandlers::add_to(HandlerTable& table) {
  table[protocol::Endpoint::PutBlob] = [this](const ApiRequest& r) { return put(r); };
  table[protocol::Endpoint::GetBlob] = [this](const ApiRequest& r) { return get(r); };
}

ApiResponse BlobHandlers::put(const ApiRequest& req) {
  const std::string& hash = req.params.at(0);
  const bool created = blobs_.put(hash, req.body);
  return json_response(created ? 201 : 200, protocol::BlobStored{hash, int64_t(req.body.size())});
}

ApiResponse BlobHandlers::get(const ApiRequest& req) {
  const std::string& hash = req.params.at(0);
  const auto file = blobs_.file(hash);
  const auto size = blobs_.size(hash);
  if (!file || !size) throw ApiError(404, "no blob " + hash);
  return file_response(*file, *size, "application/octet-stream");
}

}  // namespace vesper
