#include "cli/frame_output.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/frame_pattern.h"
#include "compositor/comp_run.h"
#include "compositor/grade.h"
#include "compositor/layer_mix.h"
#include "compositor/recipe.h"
#include "renderer/output/exr_io.h"

namespace vesper::cli {
namespace fs = std::filesystem;
namespace {

std::string lower_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::optional<ImageFormat> display_format(const fs::path& p) {
  const std::string ext = lower_extension(p);
  if (ext == ".png") return ImageFormat::Png;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::Jpeg;
  if (ext == ".tif" || ext == ".tiff") return ImageFormat::Tiff;
  return std::nullopt;
}

bool is_exr(const fs::path& p) { return lower_extension(p) == ".exr"; }

void check_not_a_folder(const fs::path& file) {
  std::error_code ec;
  if (fs::is_directory(file, ec))
    throw OutputError(file.string() + ": is a folder; give the file to write, e.g. " +
                      (file / "frame.exr").string());
}

// The folder must exist and take a new file. Creating one is the only test
// that sees everything the real write will (permissions, ACLs, read-only
// mounts, root), so a probe file is created and removed.
void check_folder(const fs::path& file) {
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::exists(dir, ec)) throw OutputError(dir.string() + ": output directory does not exist");
  if (!fs::is_directory(dir, ec)) throw OutputError(dir.string() + ": not a directory");
  const fs::path probe = dir / (".vesper-write-test-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0)
    throw OutputError(dir.string() +
                      ": cannot write in the output directory: " + std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace

FrameOutput::FrameOutput(const std::string& output, bool partial) : pattern_(output) {
  check_not_a_folder(pattern_);
  if (pattern_.has_parent_path() && pattern_.parent_path().string().find('#') != std::string::npos)
    throw OutputError(output + ": a frame pattern ('#') may only appear in the file name");
  const std::optional<ImageFormat> display = display_format(pattern_);
  if (partial) {
    if (display || is_exr(pattern_))
      throw OutputError(output +
                        ": --partial writes exact sample sums for `vesper merge`, not "
                        "an image; name it .vpartial");
    format_ = FrameFormat::Partial;
  } else if (is_exr(pattern_)) {
    format_ = FrameFormat::Exr;
  } else if (display) {
    format_ = FrameFormat::DisplayImage;
    try {  // the OCIO config ($OCIO or the bundled one): fails here, not after the render
      display_ = std::make_unique<const Grader>(GradeDesc{}, DisplayDesc{});
    } catch (const CompError& e) {
      throw OutputError(output + ": " + e.what());
    }
  } else {
    throw OutputError(output +
                      ": unknown output format; expected .exr (every layer) or .png, .jpg, .tif "
                      "(the beauty through the display transform)");
  }
  check_folder(pattern_);
}

FrameOutput::~FrameOutput() = default;

bool FrameOutput::has_frame_pattern() const { return vesper::has_frame_pattern(pattern_); }

fs::path FrameOutput::path(std::optional<long> frame) const {
  if (!has_frame_pattern()) return pattern_;
  if (!frame)
    throw OutputError(pattern_.string() +
                      ": the '#' run stands for the frame number, and there is no frame (give "
                      "--frame N, or render the partials with --frame N)");
  const fs::path p = frame_path(pattern_, *frame);
  check_not_a_folder(p);
  return p;
}

void FrameOutput::write(const LayeredImage& image, const fs::path& path) const {
  if (format_ == FrameFormat::Exr) {
    write_exr(image, path);  // logs any half clamping itself
    return;
  }
  if (format_ != FrameFormat::DisplayImage) throw std::logic_error("FrameOutput: not an image");
  RgbaImage beauty = extract_layer(image, "beauty", path.string());
  display_->apply_display(beauty);
  CompOutputs outputs;
  outputs.image = path;
  outputs.image_format = *display_format(path);
  // A hidden sibling renamed into place: the image appears whole, as EXRs do.
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  const fs::path tmp = dir / ("." + path.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                              path.extension().string());
  try {
    write_display_image(beauty, outputs, tmp, path);
    fs::rename(tmp, path);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace vesper::cli
