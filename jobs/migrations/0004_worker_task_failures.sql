-- 4: the blocklist counts the distinct tasks a worker failed in a job, so a
-- frame that crashes everywhere fails itself instead of blocking every
-- worker (the old per-worker counters are dropped: blocklists reset).
DROP TABLE worker_failures;
CREATE TABLE worker_task_failures(
  job_id INTEGER NOT NULL, worker TEXT NOT NULL, task_id INTEGER NOT NULL,
  failures INTEGER NOT NULL, PRIMARY KEY(job_id, worker, task_id));
