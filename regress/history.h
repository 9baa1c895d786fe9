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

namespace vesper {
namespace sql {
class Db;
}

namespace regress {

struct TrendLayer {
  std::string layer;
  Verdict verdict = Verdict::Pass;
  double max_abs_z = 0, min_detectable_change = 0, frame_detectable_change = 0;
  double histogram_distance = 0;
  uint64_t golden_nonfinite = 0, new_nonfinite = 0, introduced_nonfinite = 0;
  int significant_tiles = 0;
};

// One scene in one run.
struct TrendPoint {
  int64_t run = 0;  // the run's id in the database
  std::string started_at, renderer_version;
  Verdict verdict = Verdict::Pass;  // the scene's
  double golden_seconds = 0, new_seconds = 0;
  bool reused = false;
  std::vector<TrendLayer> layers;  // in the order they were recorded
};

class History {
 public:
  // Creates the file (and the schema) if needed, migrates an older one.
  explicit History(const std::filesystem::path& file);
  ~History();
  History(const History&) = delete;
  History& operator=(const History&) = delete;

  // Records the run with all its scenes and layers in one transaction;
  // returns its id.
  int64_t record(const RunResult& run);

  // The scene's last `last_n` runs (at most), oldest first.
  std::vector<TrendPoint> trend(const std::string& scene, int last_n) const;

  // Median render time of the scene over its last `last_n` rendered (not
  // reused) runs; nullopt without any.
  std::optional<double> median_seconds(const std::string& scene, int last_n) const;

 private:
  std::filesystem::path file_;
  std::unique_ptr<sql::Db> db_;
};

}  // namespace regress
}  // namespace vesper
