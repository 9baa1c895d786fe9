#pragma once
// The job model: a job is a scene plus frames, split into tasks of sample
// ranges; tasks move queued -> leased -> done/failed, and can be canceled or
// paused with their job.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vesper {

struct JobSpec {
  std::string name;
  std::string scene;        // what the worker renders: a blob hash or path, opaque to the store
  std::vector<int> frames;  // from parse_frame_range
  int spp = 16;
  int samples_per_task = 0;  // 0 = the whole frame in one task
  int priority = 50;         // higher first
  int max_attempts = 3;
};

enum class TaskState { Queued, Leased, Done, Failed, Canceled, Paused };
enum class JobState { Active, Paused, Canceled };

const char* to_string(TaskState s);
const char* to_string(JobState s);

struct Task {
  int64_t id = 0;
  int64_t job_id = 0;
  int frame = 0;
  int sample_begin = 0, sample_end = 0;
  TaskState state = TaskState::Queued;
  int attempts = 0;
  std::string worker;  // current or last lease holder
  std::string result;  // set when done
  std::string log;     // tail of the last failure's log
};

struct Lease {
  Task task;
  std::string lease_id;  // fencing token: every later call must carry it
  double expiry = 0;     // seconds, the store's clock
  std::string scene;
  int spp = 0;
};

struct JobSummary {
  int64_t id = 0;
  std::string name;
  int priority = 0;
  JobState state = JobState::Active;
  int queued = 0, leased = 0, done = 0, failed = 0, canceled = 0, paused = 0;
  int total() const { return queued + leased + done + failed + canceled + paused; }
  bool finished() const { return queued + leased + paused == 0; }
};

}  // namespace vesper
