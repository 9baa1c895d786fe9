-- 5: identical tasks are rendered once: a job's inputs key (scene, spp,
-- assets), the renderer (its executable's sha256) that produced each
-- result, and where a reused result came from.
ALTER TABLE jobs ADD COLUMN inputs_key TEXT NOT NULL DEFAULT '';
ALTER TABLE tasks ADD COLUMN renderer TEXT NOT NULL DEFAULT '';
ALTER TABLE tasks ADD COLUMN reused_from INTEGER;
CREATE INDEX tasks_done_by_range ON tasks(frame, sample_begin, sample_end) WHERE state = 'done';
