#pragma once
// The regression history (`vesper regress --history DB`): one SQLite file
// (WAL) that keeps every run's verdicts and figures, for the report's trend
// plots and for judging render time against recent runs. The schema is
// migrated like the job store's (regress/migrations/NNNN_*.sql); a database
// newer than this build is refused. Errors (std::runtime_error) name the file.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "regress/regress_result.h"
#include "regress/trend.h"

namespace vesper {
namespace sql {
class Db;
}

namespace regress {

class History {
 public:
  // Creates the file (and the schema) if needed, migrates an older one.
  explicit History(const std::filesystem::path& file);
  ~History();
  History(const History&) = delete;
  History& operator=(const History&) = delete;

  // Records the run with all its scenes (and their trend points,
  // trend_point()) and layers in one transaction; returns its id.
  int64_t record(const RunResult& run);

  // The scene's points in its last `last_n` runs (at most), oldest first.
  std::vector<TrendPoint> trend(const std::string& scene, int last_n) const;
  // Every scene's points in the last `last_runs` runs, oldest run first:
  // what write_report_html takes.
  std::vector<TrendPoint> recent_trends(int last_runs) const;

  // Median render time of the scene over its last `last_n` rendered (not
  // reused) runs; nullopt without any.
  std::optional<double> median_seconds(const std::string& scene, int last_n) const;

 private:
  std::filesystem::path file_;
  std::unique_ptr<sql::Db> db_;
};

}  // namespace regress
}  // namespace vesper
