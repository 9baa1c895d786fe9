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
  sql::Stmt(db,
            "INSERT INTO scene_results(run_id, scene, verdict, golden_seconds, new_seconds, reused)"
            " VALUES(?1, ?2, ?3, ?4, ?5, ?6)")
      .bind(1, run)
      .bind(2, scene.name)
      .bind(3, std::string(verdict_name(scene.verdict)))
      .bind(4, scene.golden_seconds)
      .bind(5, scene.new_seconds)
      .bind(6, int64_t(scene.reused))
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

std::vector<TrendLayer> layers_of(const sql::Db& db, int64_t run, const std::string& scene) {
  sql::Stmt s(db,
              "SELECT layer, verdict, max_abs_z, min_detectable_change, frame_detectable_change,"
              " histogram_distance, golden_nonfinite, new_nonfinite, introduced_nonfinite,"
              " significant_tiles FROM layer_results"
              " WHERE run_id = ?1 AND scene = ?2 ORDER BY rowid");
  s.bind(1, run).bind(2, scene);
  std::vector<TrendLayer> layers;
  while (s.step())
    layers.push_back({s.text(0), verdict_column(s, 1), s.f64(2), s.f64(3), s.f64(4), s.f64(5),
                      uint64_t(s.i64(6)), uint64_t(s.i64(7)), uint64_t(s.i64(8)), int(s.i64(9))});
  return layers;
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
  sql::Stmt s(*db_,
              "SELECT r.id, r.started_at, r.renderer_version, s.verdict, s.golden_seconds,"
              " s.new_seconds, s.reused FROM scene_results s JOIN runs r ON r.id = s.run_id"
              " WHERE s.scene = ?1 ORDER BY r.id DESC LIMIT ?2");
  s.bind(1, scene).bind(2, int64_t(std::max(last_n, 0)));
  std::vector<TrendPoint> points;
  while (s.step())
    points.push_back({s.i64(0),
                      s.text(1),
                      s.text(2),
                      verdict_column(s, 3),
                      s.f64(4),
                      s.f64(5),
                      s.i64(6) != 0,
                      {}});
  for (TrendPoint& p : points) p.layers = layers_of(*db_, p.run, scene);
  std::reverse(points.begin(), points.end());
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
