#include "worker/cache_eviction.h"

#include <sys/stat.h>

#include <algorithm>
#include <vector>

#include "common/sha256.h"

namespace fs = std::filesystem;

namespace vesper::worker_detail {
namespace {

struct Entry {
  fs::path file;
  std::string blob;
  std::uintmax_t size = 0;
  fs::file_time_type used;
};

// The cached blobs: <sha>.json and <sha> at the top of the cache dir.
std::vector<Entry> cached_blobs(const fs::path& dir) {
  std::vector<Entry> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    std::string name = e.path().filename().string();
    if (name.size() == 64 + 5 && name.ends_with(".json")) name.resize(64);
    std::error_code size_ec, time_ec;
    if (!is_sha256_hex(name) || !e.is_regular_file(size_ec)) continue;
    const auto size = e.file_size(size_ec);
    const auto used = e.last_write_time(time_ec);
    if (!size_ec && !time_ec) out.push_back({e.path(), name, size, used});
  }
  return out;
}

ino_t inode_of(const fs::path& p) {
  struct stat st {};
  return ::stat(p.c_str(), &st) == 0 ? st.st_ino : 0;
}

// Task directories (cache_dir/jobs/<key>/) holding a hard link to one of `inodes`.
void remove_task_dirs_linking(const fs::path& cache_dir, const std::set<ino_t>& inodes) {
  std::error_code ec;
  for (const auto& d : fs::directory_iterator(cache_dir / "jobs", ec)) {
    bool links = false;
    std::error_code walk_ec;
    for (const auto& f : fs::recursive_directory_iterator(d.path(), walk_ec))
      if (f.is_regular_file(walk_ec) && inodes.count(inode_of(f.path()))) {
        links = true;
        break;
      }
    if (links) fs::remove_all(d.path(), ec);
  }
}

}  // namespace

void mark_used(const fs::path& file) {
  std::error_code ec;
  fs::last_write_time(file, fs::file_time_type::clock::now(), ec);
}

Evicted evict_lru(const fs::path& cache_dir, std::uintmax_t max_bytes,
                  const std::set<std::string>& in_use) {
  std::vector<Entry> entries = cached_blobs(cache_dir);
  std::uintmax_t total = 0;
  for (const Entry& e : entries) total += e.size;
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.used < b.used; });
  Evicted out;
  std::set<ino_t> evicted_inodes;
  for (const Entry& e : entries) {
    if (total <= max_bytes) break;
    if (in_use.count(e.blob)) continue;
    const ino_t inode = inode_of(e.file);
    std::error_code ec;
    if (!fs::remove(e.file, ec)) continue;
    evicted_inodes.insert(inode);
    total -= e.size;
    ++out.blobs;
    out.bytes += e.size;
  }
  if (!evicted_inodes.empty()) remove_task_dirs_linking(cache_dir, evicted_inodes);
  return out;
}

}  // namespace vesper::worker_detail
