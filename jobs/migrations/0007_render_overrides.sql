-- 7: what a job asks of every render beyond its scene (jobs/render_overrides.h,
-- docs/farm.md "Render overrides"): the AOVs instead of the scene's
-- (comma-separated names, NULL: the scene's), the per-layer variance (0/1),
-- the seed instead of the scene's and a film scale (NULL: unset). Older jobs
-- keep rendering as before: every column is NULL or 0 for them.
ALTER TABLE jobs ADD COLUMN aovs TEXT;
ALTER TABLE jobs ADD COLUMN layer_variance INTEGER NOT NULL DEFAULT 0;
ALTER TABLE jobs ADD COLUMN seed INTEGER;
ALTER TABLE jobs ADD COLUMN scale REAL;
