-- The regression history: one row per run, per scene of a run, per layer of
-- a scene (regress/history.h). Times are ISO 8601 UTC text, durations seconds.
-- A scene's row carries its trend point (regress/trend.h): what the report plots.
CREATE TABLE runs(
  id INTEGER PRIMARY KEY,
  started_at TEXT NOT NULL,
  suite TEXT NOT NULL,
  renderer_version TEXT NOT NULL,
  verdict TEXT NOT NULL CHECK (verdict IN ('pass', 'regressed', 'error'))
);

CREATE TABLE scene_results(
  run_id INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
  scene TEXT NOT NULL,
  verdict TEXT NOT NULL CHECK (verdict IN ('pass', 'regressed', 'error')),
  golden_seconds REAL NOT NULL,
  new_seconds REAL NOT NULL,
  reused INTEGER NOT NULL,
  render_seconds REAL NOT NULL,
  max_abs_z REAL NOT NULL,
  min_detectable_change REAL NOT NULL,
  histogram_distance REAL NOT NULL,
  PRIMARY KEY (run_id, scene)
);
CREATE INDEX scene_results_by_scene ON scene_results(scene, run_id);

CREATE TABLE layer_results(
  run_id INTEGER NOT NULL,
  scene TEXT NOT NULL,
  layer TEXT NOT NULL,
  verdict TEXT NOT NULL CHECK (verdict IN ('pass', 'regressed', 'error')),
  max_abs_z REAL NOT NULL,
  min_detectable_change REAL NOT NULL,
  frame_detectable_change REAL NOT NULL,
  histogram_distance REAL NOT NULL,
  golden_nonfinite INTEGER NOT NULL,
  new_nonfinite INTEGER NOT NULL,
  introduced_nonfinite INTEGER NOT NULL,
  significant_tiles INTEGER NOT NULL,
  PRIMARY KEY (run_id, scene, layer),
  FOREIGN KEY (run_id, scene) REFERENCES scene_results(run_id, scene) ON DELETE CASCADE
);
