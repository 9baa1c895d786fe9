#pragma once
// The server's data dir is private to the user running the server, whatever
// existed before: a dir made by hand (0755) or a jobs.sqlite of an older
// server (0644) would let any local user read jobs, logs and results.
#include <filesystem>

namespace vesper {

// Creates `dir` if needed and makes it 0700; creates the job store's file
// (jobs.sqlite) 0600 when missing, so SQLite gives its -wal and -shm files
// the same mode, and makes the store's files and workers.json 0600 when
// they exist. Throws std::runtime_error naming the path when a mode cannot
// be set (a dir owned by someone else). Blobs are the BlobStore's (0600 too).
void make_data_dir_private(const std::filesystem::path& dir);

}  // namespace vesper
