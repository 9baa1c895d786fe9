-- 1: jobs, their tasks (sample ranges of frames) and per-worker failure counts.
CREATE TABLE jobs(
  id INTEGER PRIMARY KEY, name TEXT NOT NULL, scene TEXT NOT NULL, spp INTEGER NOT NULL,
  priority INTEGER NOT NULL, max_attempts INTEGER NOT NULL, state TEXT NOT NULL, created REAL NOT NULL);
CREATE TABLE tasks(
  id INTEGER PRIMARY KEY, job_id INTEGER NOT NULL REFERENCES jobs(id), frame INTEGER NOT NULL,
  sample_begin INTEGER NOT NULL, sample_end INTEGER NOT NULL, state TEXT NOT NULL,
  attempts INTEGER NOT NULL DEFAULT 0, lease_id TEXT, worker TEXT NOT NULL DEFAULT '',
  lease_expiry REAL, result TEXT NOT NULL DEFAULT '', log TEXT NOT NULL DEFAULT '');
CREATE INDEX tasks_by_state ON tasks(state, job_id);
CREATE UNIQUE INDEX tasks_by_lease ON tasks(lease_id) WHERE lease_id IS NOT NULL;
CREATE TABLE worker_failures(
  job_id INTEGER NOT NULL, worker TEXT NOT NULL, failures INTEGER NOT NULL, PRIMARY KEY(job_id, worker));
