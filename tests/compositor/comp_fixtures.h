#pragma once
// Fixtures for compositor tests: tiny synthetic multi-layer EXRs, recipe files,
// broken files (garbage bytes, a valid EXR cut in half) and a scratch folder.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/output/exr_io.h"
#include "renderer/output/layered_image.h"
#include "tests/common/temp_dir.h"

namespace vesper::comptest {

namespace fs = std::filesystem;

// A scratch folder per test, removed afterwards.
struct ScratchDir {
  test::TempDir temp{"comp-test"};
  const fs::path path = temp.path();
  fs::path operator/(const std::string& name) const { return path / name; }
};

// Every file (recursively) under `dir`, as relative paths: for "nothing was left behind".
inline std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::exists(dir, ec)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (!e.is_directory()) out.push_back(fs::relative(e.path(), dir).string());
  std::sort(out.begin(), out.end());
  return out;
}

// A layered image with the given channels; value(x, y, channel index) fills it.
inline LayeredImage make_layered(int w, int h, std::vector<std::string> channels,
                                 const std::function<float(int, int, size_t)>& value) {
  LayeredImage img;
  img.width = w;
  img.height = h;
  img.channels = std::move(channels);
  img.pixels.resize(size_t(w) * size_t(h) * img.channels.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (size_t c = 0; c < img.channels.size(); ++c) img.at(x, y, c) = value(x, y, c);
  return img;
}

// A render-like frame: surfaces + fog partition the beauty (beauty = surfaces + fog
// exactly, in float), lightrays and candles are parts of the fog, fog has an alpha.
// `scale` varies the frame (for sequences).
inline LayeredImage night_like(int w = 16, int h = 12, float scale = 1.f) {
  const std::vector<std::string> ch = {
      "R",           "G",           "B",         "A",         "surfaces.R", "surfaces.G",
      "surfaces.B",  "fog.R",       "fog.G",     "fog.B",     "fog.A",      "lightrays.R",
      "lightrays.G", "lightrays.B", "candles.R", "candles.G", "candles.B",  "depth.Z"};
  LayeredImage img = make_layered(w, h, ch, [&](int x, int y, size_t c) -> float {
    const float u = (float(x) + 0.5f) / float(w), v = (float(y) + 0.5f) / float(h);
    const float surf[3] = {0.6f * u * u * scale, 0.4f * u * v * scale, 0.2f * v * scale};
    const float rays[3] = {0.3f * v * scale, 0.28f * v * scale, 0.25f * v * scale};
    const float cand[3] = {0.5f * u * (1 - v) * scale, 0.25f * u * (1 - v) * scale,
                           0.05f * u * scale};
    // Sums in double then rounded, so that beauty == float(surf + fog) exactly.
    auto fog = [&](int k) { return rays[k] + cand[k]; };
    switch (c) {
      case 0:
      case 1:
      case 2:
        return surf[c] + fog(int(c));
      case 3:
        return 1.f;
      case 4:
      case 5:
      case 6:
        return surf[c - 4];
      case 7:
      case 8:
      case 9:
        return fog(int(c - 7));
      case 10:
        return 0.25f + 0.5f * u;
      case 11:
      case 12:
      case 13:
        return rays[c - 11];
      case 14:
      case 15:
      case 16:
        return cand[c - 14];
      default:
        return 1.f + 10.f * v;
    }
  });
  img.metadata["vesper:scene_hash"] = "test";
  return img;
}

inline void write_text(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
}

inline std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// Garbage bytes under an .exr name.
inline void write_garbage_exr(const fs::path& p) {
  std::string junk;
  for (int i = 0; i < 4096; ++i) junk.push_back(char((i * 7919 + 13) & 0xff));
  write_text(p, junk);
}

// A valid EXR cut in half.
inline void write_truncated_exr(const fs::path& p, const LayeredImage& img) {
  const fs::path full = p.string() + ".full.exr";
  write_exr(img, full);
  const std::string bytes = read_text(full);
  fs::remove(full);
  write_text(p, bytes.substr(0, bytes.size() / 2));
}

inline void write_json(const fs::path& p, const nlohmann::json& j) { write_text(p, j.dump(2)); }

}  // namespace vesper::comptest
