#pragma once
// Converged references are expensive (thousands of spp), so each is rendered
// once and kept in a cache folder (`vesper bench --refs DIR`) as an EXR named
// by what it depends on: the renderer and its cache_key (version, build), the
// scene's content hash (`vesper:scene_hash`: the scene and every file it
// reads), the size, the reference spp and the seed. Change any of them and
// the old file is simply not found.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "renderer/output/layered_image.h"

namespace vesper::measure {

struct ReferenceKey {
  std::string scene_name;  // only for the file name, so people can tell files apart
  std::string renderer, renderer_cache_key;
  std::string scene_hash;
  int width = 0, height = 0;
  int spp = 0;
  uint64_t seed = 0;  // of half A; half B uses another (bench_runner.h)
};

// 16 hex digits of the SHA-256 of every field but scene_name.
std::string reference_id(const ReferenceKey& key);
// <dir>/<scene>.<renderer>.<id>.exr
std::filesystem::path reference_path(const std::filesystem::path& dir, const ReferenceKey& key);

struct CachedReference {
  LayeredImage image;         // R, G, B: the mean of the two halves
  double noise_floor = 0;     // noise_floor.h
  double render_seconds = 0;  // both halves, as the renderer measured them
};

// The cached reference, or nullopt when there is none. A file that cannot be
// read, or whose id, size, channels or values are wrong (a truncated or
// foreign file), is also nullopt, with `warning` saying why (to be logged;
// the caller re-renders and overwrites it).
std::optional<CachedReference> load_reference(const std::filesystem::path& dir,
                                              const ReferenceKey& key, std::string* warning);

// Writes the reference atomically (creating `dir`); throws ImageIoError or
// std::filesystem::filesystem_error naming the file.
void store_reference(const std::filesystem::path& dir, const ReferenceKey& key,
                     const CachedReference& ref);

}  // namespace vesper::measure
