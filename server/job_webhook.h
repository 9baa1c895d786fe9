#pragma once
// The job webhook ([server] webhook_url; docs/farm.md, "Job lifecycle"):
// every job that ends (done, failed, canceled) is announced once with a POST
// of {"id", "name", "state", "submitted", "started"?, "finished"?, "frames",
// "failed_tasks"} from a thread of its own. It finds ended jobs in the store
// (a job's end is committed before it is announced, so a restart announces
// what a crash left unannounced); the store is only read and marked, never
// held during a POST. Each POST has a timeout and a few retries, logged; a
// job whose announcement failed every retry is given up on (logged).
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "jobs/job_store.h"

namespace vesper {

class LockedStore;

struct WebhookOptions {
  std::string url;             // http(s)://host:port/path
  double poll_seconds = 0.5;   // how often the store is looked at (or at wake())
  double timeout_seconds = 5;  // each POST
  int attempts = 3;            // POSTs per job before giving up
  double retry_seconds = 0.5;  // before the second attempt, doubling
};

// The JSON a webhook POST carries for `ended`.
nlohmann::json webhook_payload(const JobStore::EndedJob& ended);

class JobWebhook {
 public:
  JobWebhook(WebhookOptions options, LockedStore& store);
  ~JobWebhook();
  JobWebhook(const JobWebhook&) = delete;
  JobWebhook& operator=(const JobWebhook&) = delete;

  void start();
  void stop();  // the POST under way finishes (bounded by its timeout)
  void wake();  // a job may have ended: look now

 private:
  void run();
  void announce(const JobStore::EndedJob& ended);
  // Sleeps `seconds`, or until stop() (returns false) or, if `until_woken`, wake().
  bool wait(double seconds, bool until_woken);

  WebhookOptions options_;
  LockedStore& store_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stopping_ = false, woken_ = false;
};

}  // namespace vesper
