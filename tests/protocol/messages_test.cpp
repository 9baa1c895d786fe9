// The protocol's paths and messages: paths fill in as clients need them, and
// every message writes the JSON the server has always written (same keys,
// same optional keys left out) and reads it back.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "protocol/error_body.h"
#include "protocol/job_messages.h"
#include "protocol/paths.h"
#include "protocol/worker_messages.h"

namespace vesper::protocol {
namespace {

using nlohmann::json;

template <class T>
T round_trip(const T& m) {
  return json::parse(json(m).dump()).get<T>();
}

TEST(PathsTest, TemplatesFillInForClients) {
  EXPECT_EQ(api(paths::kLease), "/api/v1/lease");
  EXPECT_EQ(job_path(7), "/jobs/7");
  EXPECT_EQ(job_action_path(7, JobAction::RetryFailed), "/jobs/7/retry-failed");
  EXPECT_EQ(action_name(JobAction::Cancel), "cancel");
  EXPECT_EQ(task_log_path(7, 12), "/jobs/7/tasks/12/log");
  EXPECT_EQ(frames_path(7), "/jobs/7/frames");
  EXPECT_EQ(frame_path(7, -3), "/jobs/7/frames/-3");
  EXPECT_EQ(api(blob_path("ab")), "/api/v1/blobs/ab");
  EXPECT_THROW(expand(paths::kTaskLog, {"1"}), std::invalid_argument);
  EXPECT_THROW(expand(paths::kJobs, {"1"}), std::invalid_argument);
}

TEST(WorkerMessagesTest, LeaseRequestLeavesOutAnEmptyRenderer) {
  EXPECT_EQ(json(LeaseRequest{"w1", ""}).dump(), R"({"worker_id":"w1"})");
  EXPECT_EQ(json(LeaseRequest{"w1", "ff"}).dump(), R"({"renderer":"ff","worker_id":"w1"})");
  EXPECT_EQ(round_trip(LeaseRequest{"w1", "ff"}).renderer, "ff");
}

TEST(WorkerMessagesTest, LeaseResponseIsTheServersAnswer) {
  LeaseResponse l;
  l.lease_id = "L";
  l.expiry = 1010.5;
  l.lease_seconds = 10;
  l.scene = "S";
  l.spp = 16;
  l.assets = {{"a/b.obj", "B"}};
  l.task = {3, 1, 5, 0, 8, 1};
  EXPECT_EQ(json(l), json::parse(R"({"lease_id": "L", "expiry": 1010.5, "lease_seconds": 10.0,
                "scene": "S", "spp": 16, "assets": [{"name": "a/b.obj", "blob": "B"}],
                "task": {"id": 3, "job_id": 1, "frame": 5, "sample_begin": 0,
                         "sample_end": 8, "attempt": 1}})"));
  const LeaseResponse back = round_trip(l);
  EXPECT_EQ(back.assets, l.assets);
  EXPECT_EQ(back.task.sample_end, 8);
  EXPECT_EQ(back.lease_seconds, 10);
}

TEST(WorkerMessagesTest, SmallMessagesKeepTheirKeys) {
  EXPECT_EQ(json(RegisterRequest{"host", ""}).dump(), R"({"name":"host"})");
  EXPECT_EQ(json(RegisterRequest{"host", "w"}).dump(), R"({"name":"host","worker_id":"w"})");
  EXPECT_EQ(json(RegisterResponse{"w"}).dump(), R"({"worker_id":"w"})");
  EXPECT_EQ(json(HeartbeatRequest{"L", 0.5}).dump(), R"({"lease_id":"L","progress":0.5})");
  EXPECT_EQ(json(HeartbeatResponse{HeartbeatAnswer::KeepRunning}).dump(),
            R"({"answer":"keep_running"})");
  EXPECT_EQ(json(HeartbeatResponse{HeartbeatAnswer::Stop}).dump(), R"({"answer":"stop"})");
  EXPECT_EQ(round_trip(HeartbeatResponse{HeartbeatAnswer::Stop}).answer, HeartbeatAnswer::Stop);
  EXPECT_THROW(json::parse(R"({"answer":"maybe"})").get<HeartbeatResponse>(), json::exception);
  EXPECT_EQ(json(CompleteRequest{"L", "R", ""}).dump(), R"({"lease_id":"L","result":"R"})");
  EXPECT_EQ(json(CompleteRequest{"L", "R", "tail"}).dump(),
            R"({"lease_id":"L","log":"tail","result":"R"})");  // the render's log, optional
  EXPECT_EQ(json(FailRequest{"L", "log"}).dump(), R"({"lease_id":"L","log":"log"})");
  EXPECT_EQ(json(OkResponse{}).dump(), R"({"ok":true})");
  EXPECT_THROW(json::parse(R"({"lease_id":"L"})").get<CompleteRequest>(), json::exception);
}

TEST(JobMessagesTest, SubmitRequestCarriesFramesAsStringOrList) {
  SubmitRequest s;
  s.scene = "S";
  s.frames = std::string("1-3");
  EXPECT_EQ(json(s), json::parse(R"({"name": "job", "scene": "S", "frames": "1-3", "spp": 16,
                "samples_per_task": 0, "priority": 50, "max_attempts": 3})"));
  s.frames = std::vector<int>{1, 5};
  s.assets = {{"x", "B"}};
  const json j = s;
  EXPECT_EQ(j.at("frames"), json::parse("[1, 5]"));
  EXPECT_EQ(j.at("assets").size(), 1u);
  const SubmitRequest back = round_trip(s);
  EXPECT_EQ(std::get<std::vector<int>>(back.frames), (std::vector<int>{1, 5}));
  EXPECT_THROW(json::parse(R"({"scene": "S", "frames": "2"})").get<SubmitRequest>(),
               json::exception);
  EXPECT_THROW(json::parse(R"([1])").get<SubmitRequest>(), json::exception);
}

// A message with a render budget (submit, lease) leaves its keys out when
// unset, writes them when set, and reads them back.
template <class T>
void expect_budget_travels(T m) {
  const json unset = m;
  EXPECT_FALSE(unset.contains("noise_target") || unset.contains("min_spp") ||
               unset.contains("time_limit"));
  EXPECT_FALSE(round_trip(m).noise_target);
  m.noise_target = 0.015;
  m.min_spp = 4;
  m.time_limit = 90.5;
  const json j = m;
  EXPECT_EQ(j.at("noise_target"), 0.015);
  EXPECT_EQ(j.at("min_spp"), 4);
  EXPECT_EQ(j.at("time_limit"), 90.5);
  const T back = round_trip(m);
  EXPECT_EQ(back.noise_target, 0.015);
  EXPECT_EQ(back.min_spp, 4);
  EXPECT_EQ(back.time_limit, 90.5);
}

TEST(JobMessagesTest, TheRenderBudgetTravelsWhenSetAndIsLeftOutOtherwise) {
  SubmitRequest s;
  s.scene = "S";
  s.frames = std::string("1");
  expect_budget_travels(s);
  EXPECT_FALSE(json(s).contains("max_spp"));
  s.max_spp = 256;
  EXPECT_EQ(json(s).at("max_spp"), 256);
  EXPECT_EQ(round_trip(s).max_spp, 256);
  EXPECT_THROW(json::parse(R"({"name": "j", "scene": "S", "frames": "1", "spp": 1,
                  "samples_per_task": 0, "priority": 1, "max_attempts": 1,
                  "noise_target": "low"})")
                   .get<SubmitRequest>(),
               json::exception);

  LeaseResponse l;
  l.task = {3, 1, 5, 64, 128, 1};
  expect_budget_travels(l);
}

// The render overrides (submit, lease): left out when unset (an old job's
// messages are unchanged), written when set, read back whole.
template <class T>
void expect_overrides_travel(T m) {
  const json unset = m;
  m.aovs = {"variance", "albedo"};
  m.layer_variance = true;
  m.seed = 9007199254740993ull;  // above 2^53: kept exact as an integer
  m.scale = 0.125;
  m.half = true;
  const json set = m;
  const json expected = json::parse(R"({"aovs": ["variance", "albedo"], "layer_variance": true,
      "seed": 9007199254740993, "scale": 0.125, "half": true})");
  for (const auto& [key, value] : expected.items()) {
    EXPECT_FALSE(unset.contains(key)) << key;
    EXPECT_EQ(set.at(key), value) << key;
  }
  EXPECT_EQ(json(round_trip(m)), set);
}

TEST(JobMessagesTest, TheRenderOverridesTravelWhenSetAndAreLeftOutOtherwise) {
  SubmitRequest s;
  s.scene = "S";
  s.frames = std::string("1");
  expect_overrides_travel(s);
  LeaseResponse l;
  l.task = {3, 1, 5, 64, 128, 1};
  expect_overrides_travel(l);
}

TEST(JobMessagesTest, AReadyFrameCarriesTheNoiseItReached) {
  const FrameInfo f{4, FrameState::Ready, 2, 2, "B", "", 0.0123, 37.25, "noise_target"};
  const json j = f;
  EXPECT_EQ(j, json::parse(R"({"frame": 4, "state": "ready", "tasks": 2, "done": 2, "blob": "B",
                "noise_reached": 0.0123, "spp_mean": 37.25, "stop_reason": "noise_target"})"));
  const FrameInfo back = round_trip(f);
  EXPECT_EQ(back.noise_reached, 0.0123);
  EXPECT_EQ(back.spp_mean, 37.25);
  EXPECT_EQ(back.stop_reason, "noise_target");
  JobDetail d;
  d.frames = {f, FrameInfo{5, FrameState::Pending, 1, 0, "", "", std::nullopt, std::nullopt, ""}};
  const json dj = d;
  EXPECT_FALSE(dj.at("frames").at(1).contains("noise_reached"));
  const JobDetail db = round_trip(d);
  ASSERT_EQ(db.frames.size(), 2u);
  EXPECT_EQ(db.frames[0].spp_mean, 37.25);
  EXPECT_FALSE(db.frames[1].spp_mean);
  // An older server's answer has no frames: read as none.
  json older = d;
  older.erase("frames");
  EXPECT_TRUE(older.get<JobDetail>().frames.empty());
}

TEST(JobMessagesTest, JobDetailIsTheSummaryWithTasks) {
  JobDetail d;
  d.summary = {1, "n", 50, "active", {1, 1, 0, 0, 0, 0}, 2, 5, 6, std::nullopt, 30};
  TaskInfo leased{2,  1,     1,    0, 16,  "leased",     1,           "w",
                  "", false, 0.25, 0, 6.5, std::nullopt, std::nullopt};
  TaskInfo reused{3, 1, 2, 0, 16, "done", 0, "", "R", false, std::nullopt, 9, 7.0, 7.0, 0.0};
  d.tasks = {leased, reused};
  d.blocked_workers = {"w2"};
  const json j = d;
  EXPECT_EQ(j.at("counts").at("queued"), 1);
  EXPECT_EQ(j.at("total"), 2);
  EXPECT_EQ(j.at("tasks").at(0).at("progress"), 0.25);
  EXPECT_FALSE(j.at("tasks").at(0).contains("reused_from"));
  EXPECT_FALSE(j.at("tasks").at(1).contains("progress"));
  EXPECT_EQ(j.at("tasks").at(1).at("reused_from"), 9);
  EXPECT_EQ(j.at("blocked_workers"), json::parse(R"(["w2"])"));
  // The lifecycle's times: left out when unset.
  EXPECT_EQ(j.at("submitted"), 5);
  EXPECT_EQ(j.at("started"), 6);
  EXPECT_FALSE(j.contains("finished"));
  EXPECT_EQ(j.at("eta"), 30);
  EXPECT_EQ(j.at("tasks").at(0).at("started"), 6.5);
  EXPECT_FALSE(j.at("tasks").at(0).contains("duration"));
  EXPECT_EQ(j.at("tasks").at(1).at("duration"), 0);
  const JobDetail back = round_trip(d);
  EXPECT_EQ(back.summary.eta, 30);
  EXPECT_EQ(back.tasks.at(1).finished, 7);
  EXPECT_EQ(back.summary.name, "n");
  EXPECT_EQ(back.tasks.at(0).progress, 0.25);
  EXPECT_EQ(back.tasks.at(1).reused_from, 9);
}

TEST(JobMessagesTest, FramesWorkersActionsBlobsAndErrors) {
  FrameList frames{{{1, FrameState::Ready, 1, 1, "B", "", std::nullopt, std::nullopt, ""},
                    {2, FrameState::Failed, 2, 1, "", "x", std::nullopt, std::nullopt, ""}}};
  EXPECT_EQ(json(frames), json::parse(R"({"frames": [
      {"frame": 1, "state": "ready", "tasks": 1, "done": 1, "blob": "B"},
      {"frame": 2, "state": "failed", "tasks": 2, "done": 1, "error": "x"}]})"));
  EXPECT_EQ(round_trip(frames).frames.at(1).state, FrameState::Failed);

  WorkerList workers{{{"w", "host", 1.0, 2.0, 1, "lost", {}, {}}}, 3.0};
  EXPECT_EQ(json(workers), json::parse(R"({"workers": [{"worker_id": "w", "name": "host",
      "registered": 1.0, "last_seen": 2.0, "leases": 1, "state": "lost"}], "now": 3.0})"));
  // A worker's current task and blocklist, left out above, come back as sent.
  workers.workers[0].current_task = WorkerTask{7, 9};
  workers.workers[0].blocklisted_for = {7, 8};
  const WorkerList back = round_trip(workers);
  EXPECT_EQ(back.workers.at(0).current_task, (WorkerTask{7, 9}));
  EXPECT_EQ(back.workers.at(0).blocklisted_for, (std::vector<int64_t>{7, 8}));

  JobActionResponse a;
  a.job.id = 4;
  EXPECT_FALSE(json(a).contains("requeued"));
  a.requeued = 2;
  EXPECT_EQ(round_trip(a).requeued, 2);

  EXPECT_EQ(json(SubmitResponse{4, 6}).dump(), R"({"id":4,"task_count":6})");
  EXPECT_EQ(json(DryRunResponse{"n", 3, 6}).dump(),
            R"({"dry_run":true,"frame_count":3,"name":"n","task_count":6})");
  EXPECT_EQ(json(BlobStored{"S", 5}).dump(), R"({"sha256":"S","size":5})");
  EXPECT_EQ(json(ErrorBody{"bad", ""}).dump(), R"({"error":"bad"})");
  EXPECT_EQ(json(ErrorBody{"bad", "/frames"}).dump(), R"({"error":"bad","path":"/frames"})");
  EXPECT_EQ(round_trip(ErrorBody{"bad", "/x"}).path, "/x");
}

}  // namespace
}  // namespace vesper::protocol
