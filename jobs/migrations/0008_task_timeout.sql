-- 8: a job's task timeout, seconds one render of one of its tasks may take
-- before the worker kills it and fails that attempt. NULL: the server's
-- default (configs/farm.toml, [server] task_timeout).
ALTER TABLE jobs ADD COLUMN task_timeout REAL;
