#pragma once
// The blob cache's size cap: when the cached blobs (cache_dir/<sha>.json
// scenes, cache_dir/<sha> assets) take more than the cap, the least recently
// used go first — "used" is the file's mtime, which the worker sets each time
// a task uses the blob — never a blob the current task uses. A task
// directory under cache_dir/jobs/ holding a hard link to an evicted blob goes
// too (else the link would keep its bytes on disk); the next task that needs
// it downloads and links again.
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>

namespace vesper::worker_detail {

// Records that a task uses the cached file now (its mtime).
void mark_used(const std::filesystem::path& file);

struct Evicted {
  int blobs = 0;
  std::uintmax_t bytes = 0;
};
// Evicts least recently used blobs until the cached blobs take at most
// `max_bytes`, skipping those in `in_use` (blob hashes).
Evicted evict_lru(const std::filesystem::path& cache_dir, std::uintmax_t max_bytes,
                  const std::set<std::string>& in_use);

}  // namespace vesper::worker_detail
