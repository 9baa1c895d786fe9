#pragma once
// A finished frame as the monitor shows it: a PNG thumbnail and the
// luminosity histogram, both of the frame's composite as the compositor makes
// it with no grade — `vesper comp FRAME.exr`'s default recipe, the beauty
// added at gain 1 onto black — sRGB-encoded (IEC 61966-2-1) rather than put
// through an OCIO view. Each is made once per output blob (the name of its
// bytes, so a cached view is never stale) and kept in a cache directory;
// requests for the same view wait for one computation.
#include <filesystem>
#include <functional>
#include <mutex>
#include <string>

#include "compositor/rgba_image.h"

namespace vesper {

inline constexpr int kThumbnailMaxWidth = 256;

// The frame's composite (scene-linear RGBA). Throws CompError naming `exr`.
RgbaImage frame_composite(const std::filesystem::path& exr);
// RGB through the sRGB transfer function, clamped to [0, 1]; alpha kept.
RgbaImage srgb_encoded(const RgbaImage& linear);
// Area-averaged down to at most `max_width` columns, the aspect ratio kept
// (rows rounded, at least 1); an image already that narrow is returned as is.
RgbaImage scaled_to_width(const RgbaImage& image, int max_width);

class FrameViews {
 public:
  explicit FrameViews(std::filesystem::path cache_dir);

  // The cached file of a view of output blob `blob` (its file `exr`), made
  // first if it is not there yet. Throws CompError when the EXR cannot be read.
  std::filesystem::path thumbnail(const std::string& blob, const std::filesystem::path& exr);
  std::filesystem::path histogram(const std::string& blob, const std::filesystem::path& exr);
  // Removes the views of every blob `stored` says is gone (after blob GC);
  // returns how many files went.
  int prune(const std::function<bool(const std::string& blob)>& stored);

 private:
  template <class Make>
  std::filesystem::path cached(const std::filesystem::path& file, Make make);

  std::filesystem::path dir_;
  std::mutex mutex_;  // one view made at a time: a frame is read once, CPU stays bounded
};

}  // namespace vesper
