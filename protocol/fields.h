#pragma once
// The JSON keys of the farm API, written once. The message types
// (worker_messages.h, job_messages.h) convert with them, and the server's
// request validation names them in its error paths ("/lease_id").
namespace vesper::protocol::field {

// Errors: {"error": "...", "path": "/json/pointer"}
inline constexpr const char* kError = "error";
inline constexpr const char* kPath = "path";

// Shared by several messages.
inline constexpr const char* kId = "id";
inline constexpr const char* kName = "name";
inline constexpr const char* kState = "state";
inline constexpr const char* kFrame = "frame";
inline constexpr const char* kOk = "ok";

// Jobs
inline constexpr const char* kScene = "scene";
inline constexpr const char* kFrames = "frames";
inline constexpr const char* kSpp = "spp";
inline constexpr const char* kSamplesPerTask = "samples_per_task";
inline constexpr const char* kPriority = "priority";
inline constexpr const char* kMaxAttempts = "max_attempts";
inline constexpr const char* kAssets = "assets";
inline constexpr const char* kBlob = "blob";
inline constexpr const char* kTaskCount = "task_count";
inline constexpr const char* kFrameCount = "frame_count";
inline constexpr const char* kDryRun = "dry_run";
inline constexpr const char* kCounts = "counts";
inline constexpr const char* kQueued = "queued";
inline constexpr const char* kLeased = "leased";
inline constexpr const char* kDone = "done";
inline constexpr const char* kFailed = "failed";
inline constexpr const char* kCanceled = "canceled";
inline constexpr const char* kPaused = "paused";
inline constexpr const char* kTotal = "total";
// Job lifecycle (docs/farm.md, "Job lifecycle"): times on the server's clock
inline constexpr const char* kSubmitted = "submitted";
inline constexpr const char* kStarted = "started";
inline constexpr const char* kFinished = "finished";
inline constexpr const char* kEta = "eta";
inline constexpr const char* kDuration = "duration";
inline constexpr const char* kJobs = "jobs";
inline constexpr const char* kJob = "job";
inline constexpr const char* kTasks = "tasks";
inline constexpr const char* kBlockedWorkers = "blocked_workers";
inline constexpr const char* kTasksNext = "tasks_next";
inline constexpr const char* kRequeued = "requeued";

// Noise targets and time limits (a job's render budget) and what a frame reached
inline constexpr const char* kNoiseTarget = "noise_target";
inline constexpr const char* kMinSpp = "min_spp";
inline constexpr const char* kMaxSpp = "max_spp";
inline constexpr const char* kTimeLimit = "time_limit";
inline constexpr const char* kTaskTimeout = "task_timeout";
inline constexpr const char* kNoiseReached = "noise_reached";
inline constexpr const char* kSppMean = "spp_mean";
inline constexpr const char* kStopReason = "stop_reason";

// Render overrides: what a job asks of every render beyond its scene
inline constexpr const char* kAovs = "aovs";
inline constexpr const char* kLayerVariance = "layer_variance";
inline constexpr const char* kSeed = "seed";
inline constexpr const char* kScale = "scale";
inline constexpr const char* kHalf = "half";

// Tasks
inline constexpr const char* kJobId = "job_id";
inline constexpr const char* kSampleBegin = "sample_begin";
inline constexpr const char* kSampleEnd = "sample_end";
inline constexpr const char* kAttempts = "attempts";
inline constexpr const char* kAttempt = "attempt";
inline constexpr const char* kWorker = "worker";
inline constexpr const char* kResult = "result";
inline constexpr const char* kHasLog = "has_log";
inline constexpr const char* kProgress = "progress";
inline constexpr const char* kReusedFrom = "reused_from";

// Workers and leases
inline constexpr const char* kWorkers = "workers";
inline constexpr const char* kWorkerId = "worker_id";
inline constexpr const char* kRegistered = "registered";
inline constexpr const char* kLastSeen = "last_seen";
inline constexpr const char* kLeases = "leases";
inline constexpr const char* kNow = "now";
inline constexpr const char* kRenderer = "renderer";
inline constexpr const char* kLeaseId = "lease_id";
inline constexpr const char* kExpiry = "expiry";
inline constexpr const char* kLeaseSeconds = "lease_seconds";
inline constexpr const char* kTask = "task";
inline constexpr const char* kAnswer = "answer";
inline constexpr const char* kLog = "log";

// Worker states, job deletion (ops16)
inline constexpr const char* kCurrentTask = "current_task";
inline constexpr const char* kBlocklistedFor = "blocklisted_for";
inline constexpr const char* kDeleted = "deleted";
inline constexpr const char* kBlobsFreed = "blobs_freed";
inline constexpr const char* kBytesFreed = "bytes_freed";
inline constexpr const char* kPruned = "pruned";

// Blobs
inline constexpr const char* kSha256 = "sha256";
inline constexpr const char* kSize = "size";

}  // namespace vesper::protocol::field
