#include "regress/history.h"

#include <algorithm>

#include "jobs/migrations.h"
#include "jobs/sqlite_db.h"
#include "regress/history_migrations.h"
#include "regress/median.h"

namespace vesper::regress {
namespace {

constexpr const char* kWhat = "regression history";

Verdict verdict_column(const sql::Stmt& s, int col) {
  return parse_verdict(s.text(col)).value_or(Verdict::Error);
}

void insert_scene(sql::Db& db, int64_t run, const SceneResult& scene) {
  const TrendPoint p = trend_point(scene, "");
  sql::Stmt(db,
            "INSERT INTO scene_results(run_id, scene, verdict, golden_seconds, new_seconds, reused,"
            " render_seconds, max_abs_z, min_detectable_change, histogram_distance)"
            " VALUES(?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)")
      .bind(1, run)
      .bind(2, scene.name)
      .bind(3, std::string(verdict_name(scene.verdict)))
      .bind(4, scene.golden_seconds)
      .bind(5, scene.new_seconds)
      .bind(6, int64_t(scene.reused))
      .bind(7, p.render_seconds)
      .bind(8, p.max_abs_z)
      .bind(9, p.min_detectable_change)
      .bind(10, p.histogram_distance)
      .run();
  for (const LayerResult& l : scene.layers)
    sql::Stmt(db,
              "INSERT INTO layer_results(run_id, scene, layer, verdict, max_abs_z,"
              " min_detectable_change, frame_detectable_change, histogram_distance,"
              " golden_nonfinite, new_nonfinite, introduced_nonfinite, significant_tiles)"
              " VALUES(?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)")
        .bind(1, run)
        .bind(2, scene.name)
        .bind(3, l.layer)
        .bind(4, std::string(verdict_name(l.verdict)))
        .bind(5, l.max_abs_z)
        .bind(6, l.min_detectable_change)
        .bind(7, l.frame_detectable_change)
        .bind(8, l.histogram_distance)
        .bind(9, int64_t(l.golden_nonfinite))
        .bind(10, int64_t(l.new_nonfinite))
        .bind(11, int64_t(l.introduced_nonfinite))
        .bind(12, int64_t(l.significant_tiles))
        .run();
}

// The SELECT list read_point reads, over scene_results s joined with runs r.
constexpr const char* kPointColumns =
    "SELECT s.scene, r.started_at, s.verdict, s.render_seconds, s.reused, s.max_abs_z,"
    " s.min_detectable_change, s.histogram_distance FROM scene_results s"
    " JOIN runs r ON r.id = s.run_id ";

TrendPoint read_point(const sql::Stmt& s) {
  return {s.text(0), s.text(1), verdict_column(s, 2), s.f64(3), s.i64(4) != 0, s.f64(5),
          s.f64(6),  s.f64(7)};
}

}  // namespace

History::History(const std::filesystem::path& file)
    : file_(file), db_(std::make_unique<sql::Db>(file.string(), kWhat)) {
  db_->exec("PRAGMA journal_mode = WAL");
  db_->exec("PRAGMA foreign_keys = ON");
  sql::Transaction tx(*db_);
  migrate_schema(*db_, file.string(), kHistoryMigrations, kWhat);
  tx.commit();
}

History::~History() = default;

int64_t History::record(const RunResult& run) {
  sql::Transaction tx(*db_);
  sql::Stmt(*db_,
            "INSERT INTO runs(started_at, suite, renderer_version, verdict) VALUES(?1, ?2, ?3, ?4)")
      .bind(1, run.started_at)
      .bind(2, run.suite)
      .bind(3, run.renderer_version)
      .bind(4, std::string(verdict_name(run.verdict)))
      .run();
  const int64_t id = sqlite3_last_insert_rowid(db_->get());
  for (const SceneResult& scene : run.scenes) insert_scene(*db_, id, scene);
  tx.commit();
  return id;
}

std::vector<TrendPoint> History::trend(const std::string& scene, int last_n) const {
  sql::Stmt s(
      *db_,
      (std::string(kPointColumns) + "WHERE s.scene = ?1 ORDER BY r.id DESC LIMIT ?2").c_str());
  s.bind(1, scene).bind(2, int64_t(std::max(last_n, 0)));
  std::vector<TrendPoint> points;
  while (s.step()) points.push_back(read_point(s));
  std::reverse(points.begin(), points.end());
  return points;
}

std::vector<TrendPoint> History::recent_trends(int last_runs) const {
  sql::Stmt s(*db_, (std::string(kPointColumns) +
                     "WHERE r.id IN (SELECT id FROM runs ORDER BY id DESC LIMIT ?1)"
                     " ORDER BY r.id, s.rowid")
                        .c_str());
  s.bind(1, int64_t(std::max(last_runs, 0)));
  std::vector<TrendPoint> points;
  while (s.step()) points.push_back(read_point(s));
  return points;
}

std::optional<double> History::median_seconds(const std::string& scene, int last_n) const {
  sql::Stmt s(*db_,
              "SELECT new_seconds FROM scene_results WHERE scene = ?1 AND reused = 0"
              " AND new_seconds > 0 ORDER BY run_id DESC LIMIT ?2");
  s.bind(1, scene).bind(2, int64_t(std::max(last_n, 0)));
  std::vector<double> t;
  while (s.step()) t.push_back(s.f64(0));
  if (t.empty()) return std::nullopt;
  return median(std::move(t));
}

}  // namespace vesper::regress
