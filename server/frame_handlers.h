#pragma once
// The frame endpoints (submitter token): every frame's state, and a frame's
// EXR (merged by the FrameMerger when the frame was split).
#include "server/http_exchange.h"

namespace vesper {

class BlobStore;
class FrameMerger;
class LockedStore;

class FrameHandlers {
 public:
  FrameHandlers(LockedStore& store, const BlobStore& blobs, FrameMerger& merger)
      : store_(store), blobs_(blobs), merger_(merger) {}
  void add_to(HandlerTable& table);

 private:
  ApiResponse list(const ApiRequest& req);
  ApiResponse get(const ApiRequest& req);

  LockedStore& store_;
  const BlobStore& blobs_;
  FrameMerger& merger_;
};

}  // namespace vesper
