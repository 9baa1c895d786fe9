#pragma once
// The metadata of one sample range of a frame: what render() writes for its
// range and merge_partials() for the union of partial ranges, alike.
#include <cstdint>
#include <map>
#include <string>

#include "renderer/output/metadata_keys.h"
#include "renderer/output/metadata_text.h"

namespace vesper {

struct RangeMetadata {
  std::string scene_hash, renderer_version;
  int spp = 0;  // samples in the range
  int sample_begin = 0, sample_end = 0;
  uint64_t seed = 0;
  double render_seconds = 0;
  uint64_t nonfinite_samples = 0;
};

inline void set_range_metadata(std::map<std::string, std::string>& metadata,
                               const RangeMetadata& r) {
  namespace key = metadata_key;
  metadata[key::kSceneHash] = r.scene_hash;
  metadata[key::kSpp] = std::to_string(r.spp);
  metadata[key::kSampleBegin] = std::to_string(r.sample_begin);
  metadata[key::kSampleEnd] = std::to_string(r.sample_end);
  metadata[key::kSeed] = std::to_string(r.seed);
  metadata[key::kRendererVersion] = r.renderer_version;
  metadata[key::kRenderSeconds] = metadata_number(r.render_seconds);
  metadata[key::kNonfiniteSamples] = std::to_string(r.nonfinite_samples);
}

}  // namespace vesper
