-- 3: one output per finished frame, recorded once.
CREATE TABLE frame_outputs(
  job_id INTEGER NOT NULL REFERENCES jobs(id), frame INTEGER NOT NULL, blob TEXT NOT NULL,
  created REAL NOT NULL, PRIMARY KEY(job_id, frame));
