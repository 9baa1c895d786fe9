-- 10: jobs end and say what happened (docs/farm.md, "Job lifecycle"). A job's
-- start (first task leased or reused) and end (done, failed or canceled); a
-- task's last attempt (leased at `started`, ended at `finished`). `attempts`
-- now counts every lease; `failures` counts the failed attempts since the
-- last retry (what max_attempts limits, which `attempts` did before).
ALTER TABLE jobs ADD COLUMN started REAL;
ALTER TABLE jobs ADD COLUMN finished REAL;
ALTER TABLE tasks ADD COLUMN started REAL;
ALTER TABLE tasks ADD COLUMN finished REAL;
ALTER TABLE tasks ADD COLUMN failures INTEGER NOT NULL DEFAULT 0;
UPDATE tasks SET failures = attempts;
-- The lease a rendered done task or a live lease had was not counted.
UPDATE tasks SET attempts = attempts + 1
  WHERE state = 'leased' OR (state = 'done' AND reused_from IS NULL);
-- Jobs that ended before this schema: done or failed now (when they ended is
-- not known: `finished` stays NULL).
UPDATE jobs SET state = CASE WHEN EXISTS(SELECT 1 FROM tasks t WHERE t.job_id = jobs.id
    AND t.state = 'failed') THEN 'failed' ELSE 'done' END
  WHERE state IN ('active', 'paused') AND NOT EXISTS(SELECT 1 FROM tasks t
    WHERE t.job_id = jobs.id AND t.state IN ('queued', 'leased', 'paused'));
-- A job that ends is announced once to the webhook ([server] webhook_url);
-- those that ended before are taken as announced.
ALTER TABLE jobs ADD COLUMN announced INTEGER NOT NULL DEFAULT 0;
UPDATE jobs SET announced = 1 WHERE state IN ('done', 'failed', 'canceled');
CREATE INDEX jobs_to_announce ON jobs(id)
  WHERE announced = 0 AND state IN ('done', 'failed', 'canceled');
