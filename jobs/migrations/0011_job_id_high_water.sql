-- 11: a deleted job's id is never given to another job (`vesper delete`):
-- SQLite numbers a rowid table from its current maximum, so deleting the
-- newest job would hand its id, URLs and log lines to the next submit. The
-- highest id ever used is kept here, and submit numbers from above it.
CREATE TABLE job_id_high_water(id INTEGER NOT NULL);
INSERT INTO job_id_high_water(id) SELECT COALESCE(MAX(id), 0) FROM jobs;
CREATE TRIGGER jobs_raise_high_water AFTER INSERT ON jobs BEGIN
  UPDATE job_id_high_water SET id = MAX(id, NEW.id);
END;
