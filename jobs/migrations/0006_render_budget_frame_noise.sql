-- 6: noise targets and time limits (docs/farm.md). A job's sampling budget
-- beyond its spp (NULL: not set; with a noise target, spp is the most
-- samples a pixel takes), and what each frame's output says of its noise,
-- read from its EXR metadata once (noise_read = 1; the values stay NULL
-- when the output does not carry them).
ALTER TABLE jobs ADD COLUMN noise_target REAL;
ALTER TABLE jobs ADD COLUMN min_spp INTEGER;
ALTER TABLE jobs ADD COLUMN time_limit REAL;
ALTER TABLE frame_outputs ADD COLUMN noise_read INTEGER NOT NULL DEFAULT 0;
ALTER TABLE frame_outputs ADD COLUMN noise_reached REAL;
ALTER TABLE frame_outputs ADD COLUMN spp_mean REAL;
ALTER TABLE frame_outputs ADD COLUMN stop_reason TEXT;
CREATE INDEX frame_outputs_noise_unread ON frame_outputs(job_id, frame) WHERE noise_read = 0;
CREATE INDEX frame_outputs_noise_by_blob ON frame_outputs(blob) WHERE noise_read = 1;
