#include "protocol/worker_messages.h"

#include "protocol/fields.h"
#include "protocol/json_fields.h"

namespace vesper::protocol {

namespace f = field;
using detail::optional;
using detail::required;

VESPER_JSON_FIELDS(RegisterRequest, required(f::kName, &RegisterRequest::name),
                   optional(f::kWorkerId, &RegisterRequest::worker_id))
VESPER_JSON_FIELDS(RegisterResponse, required(f::kWorkerId, &RegisterResponse::worker_id))
VESPER_JSON_FIELDS(AssetRef, required(f::kName, &AssetRef::name),
                   required(f::kBlob, &AssetRef::blob))
VESPER_JSON_FIELDS(LeaseRequest, required(f::kWorkerId, &LeaseRequest::worker_id),
                   optional(f::kRenderer, &LeaseRequest::renderer))
VESPER_JSON_FIELDS(LeasedTask, required(f::kId, &LeasedTask::id),
                   required(f::kJobId, &LeasedTask::job_id),
                   required(f::kFrame, &LeasedTask::frame),
                   required(f::kSampleBegin, &LeasedTask::sample_begin),
                   required(f::kSampleEnd, &LeasedTask::sample_end),
                   required(f::kAttempt, &LeasedTask::attempt))
VESPER_JSON_FIELDS(
    LeaseResponse, required(f::kLeaseId, &LeaseResponse::lease_id),
    required(f::kExpiry, &LeaseResponse::expiry),
    required(f::kLeaseSeconds, &LeaseResponse::lease_seconds),
    required(f::kScene, &LeaseResponse::scene), required(f::kSpp, &LeaseResponse::spp),
    required(f::kAssets, &LeaseResponse::assets), required(f::kTask, &LeaseResponse::task),
    optional(f::kNoiseTarget, &LeaseResponse::noise_target),
    optional(f::kMinSpp, &LeaseResponse::min_spp),
    optional(f::kTimeLimit, &LeaseResponse::time_limit), optional(f::kAovs, &LeaseResponse::aovs),
    optional(f::kLayerVariance, &LeaseResponse::layer_variance),
    optional(f::kSeed, &LeaseResponse::seed), optional(f::kScale, &LeaseResponse::scale),
    optional(f::kHalf, &LeaseResponse::half),
    optional(f::kTaskTimeout, &LeaseResponse::task_timeout))
VESPER_JSON_FIELDS(HeartbeatRequest, required(f::kLeaseId, &HeartbeatRequest::lease_id),
                   required(f::kProgress, &HeartbeatRequest::progress))
VESPER_JSON_FIELDS(HeartbeatResponse, required(f::kAnswer, &HeartbeatResponse::answer))
VESPER_JSON_FIELDS(CompleteRequest, required(f::kLeaseId, &CompleteRequest::lease_id),
                   required(f::kResult, &CompleteRequest::result),
                   optional(f::kLog, &CompleteRequest::log))
VESPER_JSON_FIELDS(FailRequest, required(f::kLeaseId, &FailRequest::lease_id),
                   required(f::kLog, &FailRequest::log))
VESPER_JSON_FIELDS(OkResponse, required(f::kOk, &OkResponse::ok))

namespace {
constexpr const char* kAnswers[] = {"keep_running", "stop"};  // by HeartbeatAnswer
}  // namespace

void to_json(nlohmann::json& j, const HeartbeatAnswer& m) { detail::write_enum(j, m, kAnswers); }
void from_json(const nlohmann::json& j, HeartbeatAnswer& m) { detail::read_enum(j, m, kAnswers); }

}  // namespace vesper::protocol
