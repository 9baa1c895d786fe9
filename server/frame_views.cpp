#include "server/frame_views.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "compositor/comp_run.h"
#include "compositor/histogram.h"
#include "compositor/layer_mix.h"
#include "renderer/output/exr_io.h"

namespace vesper {
namespace fs = std::filesystem;
namespace {

// A sibling temporary name: a view appears whole (rename) or not at all.
fs::path temp_for(const fs::path& file) {
  static std::atomic<unsigned> counter{0};
  return file.parent_path() / ("." + file.filename().string() + ".tmp-" +
                               std::to_string(::getpid()) + "-" + std::to_string(counter++));
}

void write_text(const std::string& text, const fs::path& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw CompError(path.string() + ": cannot write the histogram");
}

}  // namespace

RgbaImage frame_composite(const fs::path& exr) {
  LayeredImage image;
  try {
    image = read_exr(exr);
  } catch (const ImageIoError& e) {
    throw CompError(exr.string() + ": not a readable EXR (" + e.what() + ")");
  }
  if (image.width <= 0 || image.height <= 0) throw CompError(exr.string() + ": an empty image");
  return mix_layers(image, {LayerOp{"beauty"}}, exr.string());
}

RgbaImage srgb_encoded(const RgbaImage& linear) {
  RgbaImage out = linear;
  for (size_t i = 0; i < out.pixel_count(); ++i)
    for (size_t c = 0; c < 3; ++c) {
      const float v = out.pixels[i * 4 + c];
      out.pixels[i * 4 + c] =
          std::isnan(v) ? 0.f : float(std::clamp(srgb_encode(std::min(double(v), 1.0)), 0.0, 1.0));
    }
  return out;
}

RgbaImage scaled_to_width(const RgbaImage& image, int max_width) {
  if (image.width <= max_width) return image;
  const int w = max_width;
  const int h = std::max(1, int(std::lround(double(image.height) * w / image.width)));
  RgbaImage out(w, h);
  const double sx = double(image.width) / w, sy = double(image.height) / h;
  for (int y = 0; y < h; ++y) {
    const int y0 = int(y * sy), y1 = std::max(y0 + 1, int((y + 1) * sy));
    for (int x = 0; x < w; ++x) {
      const int x0 = int(x * sx), x1 = std::max(x0 + 1, int((x + 1) * sx));
      double sum[4] = {0, 0, 0, 0};
      for (int yy = y0; yy < std::min(y1, image.height); ++yy)
        for (int xx = x0; xx < std::min(x1, image.width); ++xx)
          for (int c = 0; c < 4; ++c) sum[c] += image.at(xx, yy, c);
      const double n = double(std::min(y1, image.height) - y0) * (std::min(x1, image.width) - x0);
      for (int c = 0; c < 4; ++c) out.at(x, y, c) = float(sum[c] / n);
    }
  }
  return out;
}

FrameViews::FrameViews(fs::path cache_dir) : dir_(std::move(cache_dir)) {}

template <class Make>
fs::path FrameViews::cached(const fs::path& file, Make make) {
  std::lock_guard lock(mutex_);
  std::error_code ec;
  if (fs::is_regular_file(file, ec)) return file;
  fs::create_directories(dir_, ec);
  const fs::path tmp = temp_for(file);
  try {
    make(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, file, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw CompError(file.string() + ": cannot move the view into place: " + ec.message());
  }
  return file;
}

int FrameViews::prune(const std::function<bool(const std::string&)>& stored) {
  std::lock_guard lock(mutex_);
  std::error_code ec;
  int removed = 0;
  for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::string blob = name.substr(0, name.find('.'));  // <blob>.png, <blob>.histogram.json
    std::error_code remove_error;
    if (!stored(blob) && fs::remove(it->path(), remove_error)) ++removed;
  }
  return removed;
}

fs::path FrameViews::thumbnail(const std::string& blob, const fs::path& exr) {
  return cached(dir_ / (blob + ".png"), [&](const fs::path& tmp) {
    // Averaged in linear light, then encoded: the thumbnail's greys are the frame's.
    // A PNG as `vesper comp` writes one (8-bit, rounded, clamped).
    write_display_image(srgb_encoded(scaled_to_width(frame_composite(exr), kThumbnailMaxWidth)),
                        CompOutputs{}, tmp, dir_ / (blob + ".png"));
  });
}

fs::path FrameViews::histogram(const std::string& blob, const fs::path& exr) {
  return cached(dir_ / (blob + ".histogram.json"), [&](const fs::path& tmp) {
    const RgbaImage display = srgb_encoded(frame_composite(exr));
    nlohmann::json j = histogram_to_json(display_histogram(display, LumaWeights::Rec709));
    j["width"] = display.width;
    j["height"] = display.height;
    j["blob"] = blob;
    write_text(j.dump() + "\n", tmp);
  });
}

}  // namespace vesper
