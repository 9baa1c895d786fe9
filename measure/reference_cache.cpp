#include "measure/reference_cache.h"

#include <cmath>
#include <exception>

#include <fmt/format.h>

#include "common/sha256.h"
#include "measure/beauty.h"
#include "renderer/output/exr_io.h"
#include "renderer/output/metadata_text.h"

namespace vesper::measure {
namespace {

// Header attributes of a cached reference (read_exr keeps `vesper:*` ones).
constexpr const char* kIdKey = "vesper:bench_reference_id";
constexpr const char* kFloorKey = "vesper:bench_noise_floor";
constexpr const char* kSecondsKey = "vesper:bench_reference_seconds";

std::optional<double> number_at(const LayeredImage& img, const char* key) {
  const auto it = img.metadata.find(key);
  if (it == img.metadata.end()) return std::nullopt;
  try {
    size_t used = 0;
    const double v = std::stod(it->second, &used);
    if (used != it->second.size() || !std::isfinite(v) || v < 0) return std::nullopt;
    return v;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// Why `img` is not the reference `key` names, or "" when it is.
std::string mismatch(const LayeredImage& img, const ReferenceKey& key, const std::string& id) {
  const auto found = img.metadata.find(kIdKey);
  if (found == img.metadata.end() || found->second != id) return "its reference id differs";
  if (img.width != key.width || img.height != key.height)
    return fmt::format("it is {}x{}, expected {}x{}", img.width, img.height, key.width, key.height);
  for (float v : img.pixels)
    if (!std::isfinite(v)) return "it holds non-finite values";
  if (!number_at(img, kFloorKey) || !number_at(img, kSecondsKey))
    return "its noise floor or render time is missing";
  return "";
}

}  // namespace

std::string reference_id(const ReferenceKey& key) {
  const std::string text =
      fmt::format("vesper-bench-reference/1\n{}\n{}\n{}\n{}x{}\n{}\n{}\n", key.renderer,
                  key.renderer_cache_key, key.scene_hash, key.width, key.height, key.spp, key.seed);
  return sha256_hex(text).substr(0, 16);
}

std::filesystem::path reference_path(const std::filesystem::path& dir, const ReferenceKey& key) {
  return dir / fmt::format("{}.{}.{}.exr", key.scene_name, key.renderer, reference_id(key));
}

std::optional<CachedReference> load_reference(const std::filesystem::path& dir,
                                              const ReferenceKey& key, std::string* warning) {
  const std::filesystem::path path = reference_path(dir, key);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  std::string why;
  try {
    LayeredImage img = beauty_rgb(read_exr(path));
    why = mismatch(img, key, reference_id(key));
    if (why.empty()) {
      CachedReference ref;
      ref.noise_floor = *number_at(img, kFloorKey);
      ref.render_seconds = *number_at(img, kSecondsKey);
      ref.image = std::move(img);
      return ref;
    }
  } catch (const std::exception& e) {
    why = e.what();
  }
  if (warning)
    *warning =
        fmt::format("cached reference {} is unusable ({}); rendering it again", path.string(), why);
  return std::nullopt;
}

void store_reference(const std::filesystem::path& dir, const ReferenceKey& key,
                     const CachedReference& ref) {
  std::filesystem::create_directories(dir);
  LayeredImage img = beauty_rgb(ref.image);
  img.metadata.clear();  // a peer's image may carry keys of its own; ours say what it is
  img.metadata["vesper:scene_hash"] = key.scene_hash;
  img.metadata[kIdKey] = reference_id(key);
  img.metadata[kFloorKey] = metadata_number(ref.noise_floor);
  img.metadata[kSecondsKey] = metadata_number(ref.render_seconds);
  write_exr(img, reference_path(dir, key));
}

}  // namespace vesper::measure
