#pragma once
// A float image with named channels in OpenEXR's `layer.channel` convention
// (`R,G,B,A` for the beauty, `albedo.R`, `normal.X`, `depth.Z`, ...), plus
// metadata as text that ends up in the EXR header (typed there by
// write_exr: metadata_keys.h).
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace vesper {

struct LayeredImage {
  int width = 0, height = 0;
  std::vector<std::string> channels;
  std::vector<float> pixels;  // interleaved: (y * width + x) * channels.size() + c
  std::map<std::string, std::string> metadata;

  size_t channel_count() const { return channels.size(); }
  float& at(int x, int y, size_t c) {
    return pixels[(size_t(y) * size_t(width) + size_t(x)) * channels.size() + c];
  }
  float at(int x, int y, size_t c) const {
    return pixels[(size_t(y) * size_t(width) + size_t(x)) * channels.size() + c];
  }
  // Index of a channel by name, or -1.
  int channel_index(const std::string& name) const {
    for (size_t i = 0; i < channels.size(); ++i)
      if (channels[i] == name) return int(i);
    return -1;
  }
};

}  // namespace vesper
