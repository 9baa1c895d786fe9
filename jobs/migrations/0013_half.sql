-- 13: a render override (jobs/render_overrides.h): half-float colour channels
-- in every frame (`vesper render --half`), 0/1. Older jobs keep their float
-- frames: 0 for them.
ALTER TABLE jobs ADD COLUMN half INTEGER NOT NULL DEFAULT 0;
