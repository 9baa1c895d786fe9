#pragma once
// The blob endpoints (either token): PUT stores a body under its SHA-256
// (verified), GET streams it (HEAD answers from the same handler).
#include "server/http_exchange.h"

namespace vesper {

class BlobStore;

class BlobHandlers {
 public:
  explicit BlobHandlers(BlobStore& blobs) : blobs_(blobs) {}
  void add_to(HandlerTable& table);

 private:
  ApiResponse put(const ApiRequest& req);
  ApiResponse get(const ApiRequest& req);

  BlobStore& blobs_;
};

}  // namespace vesper
