#include "protocol/worker_messages.h"

#include <nlohmann/json.hpp>

#include "protocol/fields.h"

namespace vesper::protocol {

using nlohmann::json;
namespace f = field;

void to_json(json& j, const RegisterRequest& m) { j = {{f::kName, m.name}}; }
void from_json(const json& j, RegisterRequest& m) { j.at(f::kName).get_to(m.name); }

void to_json(json& j, const RegisterResponse& m) { j = {{f::kWorkerId, m.worker_id}}; }
void from_json(const json& j, RegisterResponse& m) { j.at(f::kWorkerId).get_to(m.worker_id); }

void to_json(json& j, const AssetRef& m) { j = {{f::kName, m.name}, {f::kBlob, m.blob}}; }
void from_json(const json& j, AssetRef& m) {
  j.at(f::kName).get_to(m.name);
  j.at(f::kBlob).get_to(m.blob);
}

void to_json(json& j, const LeaseRequest& m) {
  j = {{f::kWorkerId, m.worker_id}};
  if (!m.renderer.empty()) j[f::kRenderer] = m.renderer;
}
void from_json(const json& j, LeaseRequest& m) {
  j.at(f::kWorkerId).get_to(m.worker_id);
  m.renderer = j.value(f::kRenderer, "");
}

void to_json(json& j, const LeasedTask& m) {
  j = {{f::kId, m.id},
       {f::kJobId, m.job_id},
       {f::kFrame, m.frame},
       {f::kSampleBegin, m.sample_begin},
       {f::kSampleEnd, m.sample_end},
       {f::kAttempt, m.attempt}};
}
void from_json(const json& j, LeasedTask& m) {
  j.at(f::kId).get_to(m.id);
  j.at(f::kJobId).get_to(m.job_id);
  j.at(f::kFrame).get_to(m.frame);
  j.at(f::kSampleBegin).get_to(m.sample_begin);
  j.at(f::kSampleEnd).get_to(m.sample_end);
  j.at(f::kAttempt).get_to(m.attempt);
}

void to_json(json& j, const LeaseResponse& m) {
  j = {{f::kLeaseId, m.lease_id}, {f::kExpiry, m.expiry}, {f::kLeaseSeconds, m.lease_seconds},
       {f::kScene, m.scene},      {f::kSpp, m.spp},       {f::kAssets, m.assets},
       {f::kTask, m.task}};
}
void from_json(const json& j, LeaseResponse& m) {
  j.at(f::kLeaseId).get_to(m.lease_id);
  j.at(f::kExpiry).get_to(m.expiry);
  j.at(f::kLeaseSeconds).get_to(m.lease_seconds);
  j.at(f::kScene).get_to(m.scene);
  j.at(f::kSpp).get_to(m.spp);
  m.assets = j.value(f::kAssets, std::vector<AssetRef>{});
  j.at(f::kTask).get_to(m.task);
}

void to_json(json& j, const HeartbeatRequest& m) {
  j = {{f::kLeaseId, m.lease_id}, {f::kProgress, m.progress}};
}
void from_json(const json& j, HeartbeatRequest& m) {
  j.at(f::kLeaseId).get_to(m.lease_id);
  m.progress = j.value(f::kProgress, 0.0);
}

namespace {
constexpr const char* kKeepRunning = "keep_running";
constexpr const char* kStop = "stop";
}  // namespace

void to_json(json& j, const HeartbeatResponse& m) {
  j = {{f::kAnswer, m.keep_running ? kKeepRunning : kStop}};
}
void from_json(const json& j, HeartbeatResponse& m) {
  const std::string answer = j.at(f::kAnswer).get<std::string>();
  if (answer != kKeepRunning && answer != kStop)
    throw json::other_error::create(501, "unknown heartbeat answer '" + answer + "'", &j);
  m.keep_running = answer == kKeepRunning;
}

void to_json(json& j, const CompleteRequest& m) {
  j = {{f::kLeaseId, m.lease_id}, {f::kResult, m.result}};
}
void from_json(const json& j, CompleteRequest& m) {
  j.at(f::kLeaseId).get_to(m.lease_id);
  j.at(f::kResult).get_to(m.result);
}

void to_json(json& j, const FailRequest& m) { j = {{f::kLeaseId, m.lease_id}, {f::kLog, m.log}}; }
void from_json(const json& j, FailRequest& m) {
  j.at(f::kLeaseId).get_to(m.lease_id);
  m.log = j.value(f::kLog, "");
}

void to_json(json& j, const OkResponse&) { j = {{f::kOk, true}}; }

}  // namespace vesper::protocol
