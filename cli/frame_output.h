#pragma once
// Where `vesper render` and `vesper merge` write a frame, decided and checked
// before any work: a bad -o fails at once, not after a long render.
// - the extension picks the format: .exr (every layer), .png/.jpg/.jpeg/
//   .tif/.tiff (the beauty through the default OCIO display/view, 8-bit, as
//   `vesper comp FRAME.exr -o IMAGE` writes it), anything with --partial;
// - a run of '#' in the file name is the frame number, zero-padded to the
//   run's length (`seq.####.exr`, frame 7 -> `seq.0007.exr`);
// - the folder must exist and take a new file; the path must not be a folder.
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "renderer/output/layered_image.h"

namespace vesper {
class Grader;
}

namespace vesper::cli {

// A bad output path: a usage error (exit 2), the message names the path.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class FrameFormat { Exr, DisplayImage, Partial };

class FrameOutput {
 public:
  // `output` as given to -o. Throws OutputError: unknown extension, missing or
  // read-only folder, a folder as the output, '#' outside the file name, or
  // (display images) no usable OCIO config.
  FrameOutput(const std::string& output, bool partial);
  ~FrameOutput();

  FrameFormat format() const { return format_; }
  bool has_frame_pattern() const;
  // The file to write: the pattern filled with `frame`. Throws OutputError
  // when the name has a pattern and there is no frame.
  std::filesystem::path path(std::optional<long> frame) const;
  // Writes an EXR or display image (not a partial) atomically to `path`.
  void write(const LayeredImage& image, const std::filesystem::path& path) const;

 private:
  std::filesystem::path pattern_;
  FrameFormat format_;
  std::unique_ptr<const Grader> display_;  // display images: built up front, fails early
};

}  // namespace vesper::cli
