#pragma once
// The route table: every endpoint of the farm API with its method, path and
// the token it needs. The server registers its handlers from this table (one
// handler per Endpoint), and tests/protocol checks that docs/api/openapi.yaml
// lists exactly these routes.
#include <array>
#include <string>
#include <string_view>

#include "protocol/paths.h"

namespace vesper::protocol {

enum class Method { Get, Head, Post, Put, Delete };
std::string_view to_string(Method m);  // "GET", ...

// The bearer token a route needs (server/README.md, "Auth").
enum class Role { None, Submitter, Worker, Either };
std::string_view to_string(Role r);  // "none", "submitter", "worker", "either"

// What a route does: the server has one handler per value.
enum class Endpoint {
  Healthz,
  Metrics,
  SubmitJob,
  ListJobs,
  GetJob,
  CancelJob,
  PauseJob,
  ResumeJob,
  RetryFailed,
  TaskLog,
  ListFrames,
  GetFrame,
  RegisterWorker,
  ListWorkers,
  Lease,
  Heartbeat,
  Complete,
  Fail,
  PutBlob,
  GetBlob,  // also answers HEAD (see Route::method)
  // The browser monitor (web16): its page and assets, the cookie login, and
  // a finished frame as a thumbnail and a luminosity histogram.
  MonitorPage,
  MonitorAsset,
  Login,
  Logout,
  FrameThumbnail,
  FrameHistogram,
  // Operations on the farm's own records (issue 16, ops16).
  DeleteJob,
  WorkerGoodbye,
  PruneWorkers,
};

// Where a route's path lives: under kApiPrefix or at the server's root.
enum class Scope { Api, Root };

struct Route {
  Endpoint endpoint;
  Method method;  // Head: answered by the Get route of the same path
  Scope scope;
  std::string_view path;  // a template from paths.h
  Role role;
};

// The full path template of a route ("/api/v1/jobs/{id}").
std::string full_path(const Route& r);

// clang-format off
inline constexpr std::array kRoutes{
    Route{Endpoint::Healthz,        Method::Get,  Scope::Root, paths::kHealthz,         Role::None},
    Route{Endpoint::Healthz,        Method::Get,  Scope::Api,  paths::kHealthz,         Role::None},
    Route{Endpoint::Metrics,        Method::Get,  Scope::Root, paths::kMetrics,         Role::Either},
    Route{Endpoint::Metrics,        Method::Get,  Scope::Api,  paths::kMetrics,         Role::Either},
    Route{Endpoint::SubmitJob,      Method::Post, Scope::Api,  paths::kJobs,            Role::Submitter},
    Route{Endpoint::ListJobs,       Method::Get,  Scope::Api,  paths::kJobs,            Role::Submitter},
    Route{Endpoint::GetJob,         Method::Get,  Scope::Api,  paths::kJob,             Role::Submitter},
    Route{Endpoint::CancelJob,      Method::Post, Scope::Api,  paths::kJobCancel,       Role::Submitter},
    Route{Endpoint::PauseJob,       Method::Post, Scope::Api,  paths::kJobPause,        Role::Submitter},
    Route{Endpoint::ResumeJob,      Method::Post, Scope::Api,  paths::kJobResume,       Role::Submitter},
    Route{Endpoint::RetryFailed,    Method::Post, Scope::Api,  paths::kJobRetryFailed,  Role::Submitter},
    Route{Endpoint::TaskLog,        Method::Get,  Scope::Api,  paths::kTaskLog,         Role::Submitter},
    Route{Endpoint::ListFrames,     Method::Get,  Scope::Api,  paths::kFrames,          Role::Submitter},
    Route{Endpoint::GetFrame,       Method::Get,  Scope::Api,  paths::kFrame,           Role::Submitter},
    Route{Endpoint::RegisterWorker, Method::Post, Scope::Api,  paths::kWorkerRegister,  Role::Worker},
    Route{Endpoint::ListWorkers,    Method::Get,  Scope::Api,  paths::kWorkers,         Role::Either},
    Route{Endpoint::Lease,          Method::Post, Scope::Api,  paths::kLease,           Role::Worker},
    Route{Endpoint::Heartbeat,      Method::Post, Scope::Api,  paths::kHeartbeat,       Role::Worker},
    Route{Endpoint::Complete,       Method::Post, Scope::Api,  paths::kComplete,        Role::Worker},
    Route{Endpoint::Fail,           Method::Post, Scope::Api,  paths::kFail,            Role::Worker},
    Route{Endpoint::PutBlob,        Method::Put,  Scope::Api,  paths::kBlob,            Role::Either},
    Route{Endpoint::GetBlob,        Method::Get,  Scope::Api,  paths::kBlob,            Role::Either},
    Route{Endpoint::GetBlob,        Method::Head, Scope::Api,  paths::kBlob,            Role::Either},
    // The monitor (web16).
    Route{Endpoint::MonitorPage,    Method::Get,  Scope::Root, paths::kMonitorPage,     Role::None},
    Route{Endpoint::MonitorAsset,   Method::Get,  Scope::Root, paths::kMonitorAsset,    Role::None},
    Route{Endpoint::Login,          Method::Post, Scope::Api,  paths::kLogin,           Role::None},
    Route{Endpoint::Logout,         Method::Post, Scope::Api,  paths::kLogout,          Role::None},
    Route{Endpoint::FrameThumbnail, Method::Get,  Scope::Api,  paths::kFrameThumbnail,  Role::Submitter},
    Route{Endpoint::FrameHistogram, Method::Get,  Scope::Api,  paths::kFrameHistogram,  Role::Submitter},
    // ops16: delete a job (and collect its blobs), workers' goodbye and prune.
    Route{Endpoint::DeleteJob,      Method::Delete, Scope::Api, paths::kJob,            Role::Submitter},
    Route{Endpoint::WorkerGoodbye,  Method::Post, Scope::Api,  paths::kWorkerGoodbye,   Role::Worker},
    Route{Endpoint::PruneWorkers,   Method::Post, Scope::Api,  paths::kWorkersPrune,    Role::Submitter},
};
// clang-format on

}  // namespace vesper::protocol
