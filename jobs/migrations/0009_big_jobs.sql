-- 9: big jobs (a job may hold 100 000 tasks): what a lease, a completion, a
-- frame's status and a page of a job's task list need is found through an
-- index instead of a scan of every task. Queued tasks by job in leasing order;
-- every task by job and frame (frame status, task pages); the later sample
-- ranges of split frames (the frames that may wait for a merge).
CREATE INDEX tasks_queued_by_job ON tasks(job_id, frame, sample_begin) WHERE state = 'queued';
CREATE INDEX tasks_by_job_frame ON tasks(job_id, frame, sample_begin);
-- (sample_begin too: a covering index, or the planner prefers the full one)
CREATE INDEX tasks_split_frames ON tasks(job_id, frame, sample_begin) WHERE sample_begin > 0;
