#pragma once
// The job store behind a mutex: JobStore holds one SQLite connection, so one
// caller at a time. Every call is one short transaction; blob hashing and
// file I/O run outside the lock.
#include <memory>
#include <mutex>
#include <utility>

#include "jobs/job_store.h"

namespace vesper {

class LockedStore {
 public:
  explicit LockedStore(std::unique_ptr<JobStore> store) : store_(std::move(store)) {}

  // Runs f(JobStore&) under the lock and returns what it returns.
  template <class F>
  decltype(auto) with(F&& f) {
    std::lock_guard lock(mutex_);
    return std::forward<F>(f)(*store_);
  }

 private:
  std::mutex mutex_;
  std::unique_ptr<JobStore> store_;
};

// The job, or ApiError 404 "no job N". Call inside LockedStore::with.
JobSummary require_job(JobStore& store, int64_t id);

}  // namespace vesper
