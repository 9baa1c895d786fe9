#pragma once
// The job store behind locks. JobStore holds one SQLite connection, so one
// caller at a time: every change goes through with(), one short transaction
// under the writers' mutex. Reads that list (jobs, a job's task pages and
// frames, metrics) go through read(): a second connection to the same file,
// with its own mutex and a read snapshot, so a client reading a 100 000-task
// job never holds up a lease (WAL lets readers and a writer run together).
// Blob hashing and file I/O run outside both locks.
#include <memory>
#include <mutex>
#include <utility>

#include "jobs/job_store.h"

namespace vesper {

class LockedStore {
 public:
  // `reader`: a second JobStore on the same file; null = reads share the writer.
  explicit LockedStore(std::unique_ptr<JobStore> writer, std::unique_ptr<JobStore> reader = {})
      : store_(std::move(writer)), reader_(std::move(reader)) {}

  // Runs f(JobStore&) under the writers' lock and returns what it returns.
  template <class F>
  decltype(auto) with(F&& f) {
    std::lock_guard lock(mutex_);
    return std::forward<F>(f)(*store_);
  }

  // Runs f(const JobStore&) on the reading connection, every read of it
  // seeing one committed state; never waits for a writer.
  template <class F>
  decltype(auto) read(F&& f) {
    if (!reader_) return with([&](JobStore& s) { return std::forward<F>(f)(std::as_const(s)); });
    std::lock_guard lock(read_mutex_);
    JobStore::ReadSnapshot snapshot(*reader_);
    return std::forward<F>(f)(std::as_const(*reader_));
  }

 private:
  std::mutex mutex_, read_mutex_;
  std::unique_ptr<JobStore> store_, reader_;
};

// The job, or ApiError 404 "no job N". Call inside LockedStore::with or read.
JobSummary require_job(const JobStore& store, int64_t id);

}  // namespace vesper
