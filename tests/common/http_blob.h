#pragma once
// Uploading a blob to a farm server in tests: PUT /api/v1/blobs/<sha256>
// with the given token headers, expecting 201 (stored) or 200 (already
// there). For the suites that run a server (server/, worker/).
#include <gtest/gtest.h>
#include <httplib.h>

#include <string>

#include "common/sha256.h"

namespace vesper::test {

// Returns the blob's hash (the test fails if the server does not store it).
inline std::string upload_blob(httplib::Client&& client, const httplib::Headers& auth,
                               const std::string& bytes) {
  const std::string hash = sha256_hex(bytes);
  auto r = client.Put(("/api/v1/blobs/" + hash).c_str(), auth, bytes, "application/octet-stream");
  EXPECT_TRUE(r);
  if (r) {
    EXPECT_TRUE(r->status == 201 || r->status == 200) << r->body;
  }
  return hash;
}

}  // namespace vesper::test
