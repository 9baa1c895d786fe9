#include "protocol/job_messages.h"

#include "protocol/fields.h"
#include "protocol/json_fields.h"

// A frame selection is a range string or a list of frames.
template <>
struct nlohmann::adl_serializer<std::variant<std::string, std::vector<int>>> {
  static void to_json(json& j, const std::variant<std::string, std::vector<int>>& v) {
    std::visit([&](const auto& frames) { j = frames; }, v);
  }
  static void from_json(const json& j, std::variant<std::string, std::vector<int>>& v) {
    if (j.is_string())
      v = j.get<std::string>();
    else
      v = j.get<std::vector<int>>();
  }
};

namespace vesper::protocol {

namespace f = field;
using detail::optional;
using detail::required;

VESPER_JSON_FIELDS(
    SubmitRequest, required(f::kName, &SubmitRequest::name),
    required(f::kScene, &SubmitRequest::scene), required(f::kFrames, &SubmitRequest::frames),
    required(f::kSpp, &SubmitRequest::spp),
    required(f::kSamplesPerTask, &SubmitRequest::samples_per_task),
    required(f::kPriority, &SubmitRequest::priority),
    required(f::kMaxAttempts, &SubmitRequest::max_attempts),
    optional(f::kAssets, &SubmitRequest::assets),
    optional(f::kNoiseTarget, &SubmitRequest::noise_target),
    optional(f::kMinSpp, &SubmitRequest::min_spp), optional(f::kMaxSpp, &SubmitRequest::max_spp),
    optional(f::kTimeLimit, &SubmitRequest::time_limit), optional(f::kAovs, &SubmitRequest::aovs),
    optional(f::kLayerVariance, &SubmitRequest::layer_variance),
    optional(f::kSeed, &SubmitRequest::seed), optional(f::kScale, &SubmitRequest::scale),
    optional(f::kHalf, &SubmitRequest::half),
    optional(f::kTaskTimeout, &SubmitRequest::task_timeout))
VESPER_JSON_FIELDS(SubmitResponse, required(f::kId, &SubmitResponse::id),
                   required(f::kTaskCount, &SubmitResponse::task_count))
VESPER_JSON_FIELDS(DryRunResponse, required(f::kDryRun, &DryRunResponse::dry_run),
                   required(f::kName, &DryRunResponse::name),
                   required(f::kFrameCount, &DryRunResponse::frame_count),
                   required(f::kTaskCount, &DryRunResponse::task_count))
VESPER_JSON_FIELDS(JobCounts, required(f::kQueued, &JobCounts::queued),
                   required(f::kLeased, &JobCounts::leased), required(f::kDone, &JobCounts::done),
                   required(f::kFailed, &JobCounts::failed),
                   required(f::kCanceled, &JobCounts::canceled),
                   required(f::kPaused, &JobCounts::paused))
VESPER_JSON_FIELDS(
    JobSummary, required(f::kId, &JobSummary::id), required(f::kName, &JobSummary::name),
    required(f::kPriority, &JobSummary::priority), required(f::kState, &JobSummary::state),
    required(f::kCounts, &JobSummary::counts), required(f::kTotal, &JobSummary::total),
    optional(f::kSubmitted, &JobSummary::submitted), optional(f::kStarted, &JobSummary::started),
    optional(f::kFinished, &JobSummary::finished), optional(f::kEta, &JobSummary::eta))
VESPER_JSON_FIELDS(JobList, required(f::kJobs, &JobList::jobs), optional(f::kNow, &JobList::now))
VESPER_JSON_FIELDS(
    TaskInfo, required(f::kId, &TaskInfo::id), required(f::kJobId, &TaskInfo::job_id),
    required(f::kFrame, &TaskInfo::frame), required(f::kSampleBegin, &TaskInfo::sample_begin),
    required(f::kSampleEnd, &TaskInfo::sample_end), required(f::kState, &TaskInfo::state),
    required(f::kAttempts, &TaskInfo::attempts), required(f::kWorker, &TaskInfo::worker),
    required(f::kResult, &TaskInfo::result), required(f::kHasLog, &TaskInfo::has_log),
    optional(f::kProgress, &TaskInfo::progress), optional(f::kReusedFrom, &TaskInfo::reused_from),
    optional(f::kStarted, &TaskInfo::started), optional(f::kFinished, &TaskInfo::finished),
    optional(f::kDuration, &TaskInfo::duration))
VESPER_JSON_FIELDS(JobActionResponse, required(f::kJob, &JobActionResponse::job),
                   optional(f::kRequeued, &JobActionResponse::requeued))
VESPER_JSON_FIELDS(FrameInfo, required(f::kFrame, &FrameInfo::frame),
                   required(f::kState, &FrameInfo::state), required(f::kTasks, &FrameInfo::tasks),
                   required(f::kDone, &FrameInfo::done), optional(f::kBlob, &FrameInfo::blob),
                   optional(f::kError, &FrameInfo::error),
                   optional(f::kNoiseReached, &FrameInfo::noise_reached),
                   optional(f::kSppMean, &FrameInfo::spp_mean),
                   optional(f::kStopReason, &FrameInfo::stop_reason))
VESPER_JSON_FIELDS(FrameList, required(f::kFrames, &FrameList::frames))
VESPER_JSON_FIELDS(WorkerInfo, required(f::kWorkerId, &WorkerInfo::worker_id),
                   required(f::kName, &WorkerInfo::name),
                   required(f::kRegistered, &WorkerInfo::registered),
                   required(f::kLastSeen, &WorkerInfo::last_seen),
                   required(f::kLeases, &WorkerInfo::leases),
                   optional(f::kState, &WorkerInfo::state),
                   optional(f::kCurrentTask, &WorkerInfo::current_task),
                   optional(f::kBlocklistedFor, &WorkerInfo::blocklisted_for))
VESPER_JSON_FIELDS(WorkerTask, required(f::kJob, &WorkerTask::job),
                   required(f::kTask, &WorkerTask::task))
VESPER_JSON_FIELDS(WorkerList, required(f::kWorkers, &WorkerList::workers),
                   required(f::kNow, &WorkerList::now))
VESPER_JSON_FIELDS(BlobStored, required(f::kSha256, &BlobStored::sha256),
                   required(f::kSize, &BlobStored::size))

namespace {
// The fields JobDetail adds to its summary's (one flat object on the wire).
constexpr auto kJobDetailFields =
    std::tuple{required(f::kTasks, &JobDetail::tasks),
               required(f::kBlockedWorkers, &JobDetail::blocked_workers),
               optional(f::kFrames, &JobDetail::frames),
               optional(f::kTasksNext, &JobDetail::tasks_next), optional(f::kNow, &JobDetail::now)};
constexpr const char* kFrameStates[] = {"pending", "ready", "failed"};  // by FrameState
}  // namespace

void to_json(nlohmann::json& j, const JobDetail& m) {
  j = m.summary;
  detail::write_fields(j, m, kJobDetailFields);
}
void from_json(const nlohmann::json& j, JobDetail& m) {
  j.get_to(m.summary);
  detail::read_fields(j, m, kJobDetailFields);
}

void to_json(nlohmann::json& j, const FrameState& m) { detail::write_enum(j, m, kFrameStates); }
void from_json(const nlohmann::json& j, FrameState& m) { detail::read_enum(j, m, kFrameStates); }

}  // namespace vesper::protocol
