#pragma once
// The scheduling policy: which queued task a worker gets next.
#include <cstdint>
#include <optional>
#include <string>

namespace vesper {

namespace sql {
class Db;
}

// The best queued task of an active job for `worker`, or nothing: jobs this
// worker failed `blocklist_threshold` distinct tasks of are skipped; then the
// highest priority, the oldest job, tasks this worker has not failed before
// those it has (a retry goes elsewhere when it can), the lowest frame and
// sample range first.
std::optional<int64_t> next_task(const sql::Db& db, const std::string& worker,
                                 int blocklist_threshold);

}  // namespace vesper
