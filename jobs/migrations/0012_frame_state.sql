-- 12: a scene over time (keyframes, per-frame files) has a state per frame:
-- result reuse keys a task on its frame's state (jobs/frame_states.h), so a
-- frame whose evaluated scene did not change is not rendered twice. '' for
-- tasks of jobs submitted without one (reuse keys on the job's scene blob).
ALTER TABLE tasks ADD COLUMN frame_state TEXT NOT NULL DEFAULT '';
