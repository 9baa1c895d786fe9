-- 2: assets (files the scene references) travel as blobs; a lease carries its
-- job's assets in submission order (ord).
CREATE TABLE job_assets(
  job_id INTEGER NOT NULL REFERENCES jobs(id), ord INTEGER NOT NULL, name TEXT NOT NULL,
  blob TEXT NOT NULL, PRIMARY KEY(job_id, ord), UNIQUE(job_id, name));
