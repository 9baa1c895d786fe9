#include "worker/task_dir.h"

#include <stdexcept>
#include <system_error>

#include "common/sha256.h"

namespace fs = std::filesystem;

namespace vesper::worker_detail {
namespace {

// True if `p` (made absolute and with symlinks resolved as far as they exist)
// lies strictly inside `dir`.
bool inside(const fs::path& dir, const fs::path& p) {
  std::error_code ec;
  const fs::path d = fs::weakly_canonical(dir, ec);
  if (ec) return false;
  const fs::path q = fs::weakly_canonical(p, ec);
  if (ec) return false;
  auto di = d.begin(), qi = q.begin();
  for (; di != d.end(); ++di, ++qi)
    if (qi == q.end() || *di != *qi) return false;
  return qi != q.end();
}

// The file at `place` is the cached blob `cached` (hash `blob`).
bool same_file(const fs::path& place, const fs::path& cached, const std::string& blob) {
  std::error_code ec;
  if (fs::equivalent(place, cached, ec)) return true;
  return fs::is_regular_file(place, ec) && sha256_file(place) == blob;
}

bool complete(const fs::path& dir, const fs::path& cache_dir, const std::string& scene,
              const std::vector<Asset>& assets) {
  if (!same_file(dir / "scene.json", cache_dir / (scene + ".json"), scene)) return false;
  for (const Asset& a : assets)
    if (!same_file(dir / a.name, asset_cache_file(cache_dir, a.blob), a.blob)) return false;
  return true;
}

void link_or_copy(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::create_hard_link(from, to, ec);
  if (!ec) return;
  fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
  if (ec)
    throw std::runtime_error("cannot link or copy " + from.string() + " to " + to.string() + ": " +
                             ec.message());
}

}  // namespace

fs::path asset_cache_file(const fs::path& cache_dir, const std::string& blob) {
  return cache_dir / blob;
}

std::string task_dir_key(const std::string& scene, const std::vector<Asset>& assets) {
  if (assets.empty()) return scene;
  std::string manifest = "vesper-task-dir/1\n" + scene + "\n";
  for (const Asset& a : assets) {
    manifest += a.name;
    manifest += '\0';
    manifest += a.blob + "\n";
  }
  return sha256_hex(manifest);
}

fs::path materialise_task_dir(const fs::path& cache_dir, const std::string& scene,
                              const std::vector<Asset>& assets, const std::string& unique) {
  if (!is_sha256_hex(scene)) throw std::runtime_error("malformed scene hash '" + scene + "'");
  for (const Asset& a : assets) {
    if (const std::string why = asset_name_problem(a.name); !why.empty())
      throw std::runtime_error("asset name '" + a.name + "' " + why);
    if (a.name == "scene.json")
      throw std::runtime_error("asset name 'scene.json' clashes with the scene");
    if (!is_sha256_hex(a.blob))
      throw std::runtime_error("malformed blob hash '" + a.blob + "' of asset '" + a.name + "'");
  }
  const fs::path dir = cache_dir / "jobs" / task_dir_key(scene, assets);
  if (complete(dir, cache_dir, scene, assets)) return dir;

  std::error_code ec;
  fs::create_directories(cache_dir / "jobs", ec);
  const fs::path tmp = cache_dir / "tmp" / ("taskdir-" + unique);
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) throw std::runtime_error("cannot create " + tmp.string() + ": " + ec.message());
  try {
    link_or_copy(cache_dir / (scene + ".json"), tmp / "scene.json");
    for (const Asset& a : assets) {
      const fs::path target = tmp / fs::path(a.name);
      // The server validated the names; check again before writing anything.
      if (!inside(tmp, target))
        throw std::runtime_error("asset name '" + a.name + "' resolves outside the task directory");
      fs::create_directories(target.parent_path(), ec);
      if (ec)
        throw std::runtime_error("cannot create " + target.parent_path().string() + ": " +
                                 ec.message());
      if (!inside(tmp, target))
        throw std::runtime_error("asset name '" + a.name + "' resolves outside the task directory");
      if (fs::exists(fs::symlink_status(target)))
        throw std::runtime_error("asset name '" + a.name + "' clashes with another asset");
      link_or_copy(asset_cache_file(cache_dir, a.blob), target);
    }
    fs::rename(tmp, dir, ec);
    if (ec) {
      // Another worker put it there first, or a stale/corrupt one is in the way.
      if (complete(dir, cache_dir, scene, assets)) {
        fs::remove_all(tmp, ec);
        return dir;
      }
      const fs::path stale = cache_dir / "tmp" / ("stale-" + unique);
      fs::rename(dir, stale, ec);
      fs::remove_all(stale, ec);
      fs::rename(tmp, dir, ec);
      if (ec && !complete(dir, cache_dir, scene, assets))
        throw std::runtime_error("cannot move the task directory into " + dir.string() + ": " +
                                 ec.message());
      fs::remove_all(tmp, ec);
    }
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  return dir;
}

}  // namespace vesper::worker_detail
