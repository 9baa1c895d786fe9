#pragma once
// The worker protocol's messages (server/README.md, "Worker protocol";
// docs/api/openapi.yaml): register, lease, heartbeat, complete, fail. Each
// converts to and from its JSON body with nlohmann's to_json/from_json;
// from_json throws nlohmann::json::exception on a missing key or wrong type
// (the server validates requests itself, with JSON paths in its errors).
#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace vesper::protocol {

// POST /workers/register
struct RegisterRequest {
  std::string name;  // at most 128 characters
};
struct RegisterResponse {
  std::string worker_id;
};

// A file the scene references, sent as a blob: `name` is the relative path
// the scene uses, `blob` the SHA-256 of its bytes.
struct AssetRef {
  std::string name;
  std::string blob;
  bool operator==(const AssetRef&) const = default;
};

// POST /lease
struct LeaseRequest {
  std::string worker_id;
  // SHA-256 of the worker's renderer executable: identical tasks it already
  // rendered are not rendered again. Empty: not sent, nothing is reused.
  std::string renderer;
};

// The leased task's place in its job.
struct LeasedTask {
  int64_t id = 0;
  int64_t job_id = 0;
  int frame = 0;
  int sample_begin = 0, sample_end = 0;
  int attempt = 0;  // 1 for the first
};

// 200 answer to POST /lease (204 without a body: nothing to do).
struct LeaseResponse {
  std::string lease_id;  // fencing token: every later call carries it
  double expiry = 0;     // the server's clock, seconds
  double lease_seconds = 0;
  std::string scene;  // blob
  int spp = 0;
  std::vector<AssetRef> assets;
  LeasedTask task;
};

// POST /heartbeat
struct HeartbeatRequest {
  std::string lease_id;
  double progress = 0;  // 0..1
};
// {"answer": "keep_running"} (the lease is extended) or {"answer": "stop"}
// (the job was canceled or paused: drop the task).
struct HeartbeatResponse {
  bool keep_running = true;
};

// POST /complete: the result blob is uploaded first.
struct CompleteRequest {
  std::string lease_id;
  std::string result;  // SHA-256 of the result blob
};

// POST /fail
struct FailRequest {
  std::string lease_id;
  std::string log;  // tail of the render's log; the server keeps the last 64 KiB
};

// {"ok": true}: the answer to /complete and /fail.
struct OkResponse {};

void to_json(nlohmann::json& j, const RegisterRequest& m);
void from_json(const nlohmann::json& j, RegisterRequest& m);
void to_json(nlohmann::json& j, const RegisterResponse& m);
void from_json(const nlohmann::json& j, RegisterResponse& m);
void to_json(nlohmann::json& j, const AssetRef& m);
void from_json(const nlohmann::json& j, AssetRef& m);
void to_json(nlohmann::json& j, const LeaseRequest& m);
void from_json(const nlohmann::json& j, LeaseRequest& m);
void to_json(nlohmann::json& j, const LeasedTask& m);
void from_json(const nlohmann::json& j, LeasedTask& m);
void to_json(nlohmann::json& j, const LeaseResponse& m);
void from_json(const nlohmann::json& j, LeaseResponse& m);
void to_json(nlohmann::json& j, const HeartbeatRequest& m);
void from_json(const nlohmann::json& j, HeartbeatRequest& m);
void to_json(nlohmann::json& j, const HeartbeatResponse& m);
void from_json(const nlohmann::json& j, HeartbeatResponse& m);
void to_json(nlohmann::json& j, const CompleteRequest& m);
void from_json(const nlohmann::json& j, CompleteRequest& m);
void to_json(nlohmann::json& j, const FailRequest& m);
void from_json(const nlohmann::json& j, FailRequest& m);
void to_json(nlohmann::json& j, const OkResponse& m);

}  // namespace vesper::protocol
