// run_comp: recipe -> graded EXR, display image, luminosity histogram (comp_run.h).
#include "compositor/comp_run.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <optional>
#include <system_error>

#include "common/frame_pattern.h"
#include "compositor/grade.h"
#include "renderer/output/exr_io.h"
#include "renderer/output/metadata_keys.h"

namespace vesper {
namespace fs = std::filesystem;
namespace {

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

// Temporary files of one frame: each output is written to a hidden sibling of
// its final path (same folder, so the rename is atomic and never crosses a
// filesystem) and renamed by commit(); anything not committed is removed.
class FrameFiles {
 public:
  ~FrameFiles() {
    std::error_code ec;
    for (const auto& [tmp, final_path] : files_) fs::remove(tmp, ec);
  }
  // A temporary path for `final_path`, keeping its extension (writers choose
  // the format by it).
  fs::path temp_for(const fs::path& final_path) {
    static std::atomic<unsigned> counter{0};
    const fs::path dir = final_path.has_parent_path() ? final_path.parent_path() : fs::path(".");
    std::string name = ".";  // built with += (gcc 12 warns falsely on "." + std::string)
    name += final_path.stem().string();
    name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    name += final_path.extension().string();
    const fs::path tmp = dir / name;
    files_.emplace_back(tmp, final_path);
    return tmp;
  }
  void commit() {
    std::error_code ec;
    for (size_t i = 0; i < files_.size(); ++i) {
      fs::rename(files_[i].first, files_[i].second, ec);
      if (ec) {
        const std::string msg =
            "cannot move the finished file to " + files_[i].second.string() + ": " + ec.message();
        // Undo the renames already done: a frame is all or nothing.
        for (size_t j = 0; j < i; ++j) fs::remove(files_[j].second, ec);
        throw CompError(msg);
      }
    }
    files_.clear();
  }

 private:
  std::vector<std::pair<fs::path, fs::path>> files_;
};

void write_text(const fs::path& path, const std::string& text, const fs::path& final_path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw CompError(final_path.string() + ": cannot write the file");
}

LayeredImage read_input(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw CompError(path.string() + ": no such file");
  try {
    // Every part of a multi-part file (Nuke's and Blender's layout).
    LayeredImage img = read_exr_all_parts(path);
    if (img.width <= 0 || img.height <= 0 || img.channels.empty())
      throw CompError(path.string() + ": an empty image");
    return img;
  } catch (const ExrPartsError& e) {
    throw CompError(e.what());
  } catch (const ImageIoError& e) {
    throw CompError(path.string() + ": not a readable EXR (" + e.what() + ")");
  }
}

}  // namespace

void write_display_image(const RgbaImage& display, const CompOutputs& o, const fs::path& tmp,
                         const fs::path& final_path) {
  const std::vector<uint16_t> q = quantize_rgb(display, o.bit_depth);
  const char* format = o.image_format == ImageFormat::Png    ? "png"
                       : o.image_format == ImageFormat::Jpeg ? "jpeg"
                                                             : "tiff";
  auto out = OIIO::ImageOutput::create(format);
  if (!out)
    throw CompError(final_path.string() + ": no " + format + " writer: " + OIIO::geterror());
  const OIIO::TypeDesc type = o.bit_depth == 16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(display.width, display.height, 3, type);
  if (o.image_format == ImageFormat::Jpeg) spec.attribute("Compression", "jpeg:95");
  if (o.image_format == ImageFormat::Tiff) spec.attribute("compression", "zip");
  spec.attribute("Software", "vesper comp");
  bool ok = out->open(tmp.string(), spec);
  if (ok) {
    if (o.bit_depth == 16) {
      ok = out->write_image(type, q.data());
    } else {
      std::vector<uint8_t> bytes(q.begin(), q.end());
      ok = out->write_image(type, bytes.data());
    }
  }
  const bool closed = ok && out->close();
  if (!ok || !closed) throw CompError(final_path.string() + ": cannot write: " + out->geterror());
}

namespace {

fs::path at_frame(const fs::path& p, std::optional<long> frame) {
  return frame ? frame_path(p, *frame) : p;
}

// The inputs one frame's layers use, each read once.
struct FrameInputs {
  std::vector<LayeredImage> images;
  std::vector<fs::path> paths;
};

FrameInputs read_frame_inputs(const CompRecipe& recipe, std::optional<long> frame) {
  FrameInputs in;
  in.images.resize(recipe.inputs.size());
  in.paths.resize(recipe.inputs.size());
  std::vector<bool> loaded(recipe.inputs.size(), false);
  for (const CompLayer& l : recipe.layers) {
    if (l.input >= recipe.inputs.size()) throw CompError(recipe.label + ": bad input index");
    if (loaded[l.input]) continue;
    const CompInput& input = recipe.inputs[l.input];
    in.paths[l.input] = input.sequence ? at_frame(input.path, frame) : input.path;
    in.images[l.input] = read_input(in.paths[l.input]);
    loaded[l.input] = true;
  }
  return in;
}

// The layers mixed onto a canvas the size of the first layer's image.
RgbaImage mix_frame(const CompRecipe& recipe, const FrameInputs& in) {
  const LayeredImage& first = in.images[recipe.layers.front().input];
  RgbaImage canvas(first.width, first.height);
  for (const CompLayer& l : recipe.layers) {
    const LayeredImage& img = in.images[l.input];
    const std::string source = in.paths[l.input].string();
    const std::vector<std::string> available = list_layers(img);
    if (std::find(available.begin(), available.end(), l.op.layer) == available.end()) {
      throw CompError(recipe.label + ": " + l.json_path + ": no layer '" + l.op.layer + "' in " +
                      source + " (layers: " + join(available) + ")");
    }
    if (img.width != canvas.width || img.height != canvas.height) {
      throw CompError(recipe.label + ": " + l.json_path + ": " + source + " is " +
                      std::to_string(img.width) + "x" + std::to_string(img.height) +
                      ", the composite " + std::to_string(canvas.width) + "x" +
                      std::to_string(canvas.height));
    }
    blend_layer(canvas, extract_layer(img, l.op.layer, source), l.op);
  }
  return canvas;
}

// The graded scene-linear composite, with the first input's metadata.
void write_graded_exr(const RgbaImage& canvas, const LayeredImage& first,
                      const std::string& recipe_label, const fs::path& tmp,
                      const fs::path& final_path) {
  LayeredImage exr;
  exr.width = canvas.width;
  exr.height = canvas.height;
  exr.channels = {"R", "G", "B", "A"};
  exr.pixels = canvas.pixels;
  exr.metadata = first.metadata;  // its encoding too (half, codec): write_exr counts anew
  exr.metadata.erase(metadata_key::kHalfClamped);
  exr.metadata[metadata_key::kCompRecipe] = recipe_label;
  exr.metadata[metadata_key::kCompColorspace] = "scene_linear (graded)";
  try {
    write_exr(exr, tmp);
  } catch (const ImageIoError& e) {
    throw CompError(final_path.string() + ": cannot write: " + e.what());
  }
}

// Refuses a graded composite holding NaN or infinity (extreme but accepted
// grades and gains on bright pixels, or such values in an input): it would
// be written into the EXR and hide in the display image as black.
void expect_finite(const RgbaImage& graded, const std::string& recipe_label,
                   std::optional<long> frame) {
  size_t bad = 0;
  for (float v : graded.pixels) bad += !std::isfinite(v);
  if (bad == 0) return;
  throw CompError(recipe_label + ": " + (frame ? "frame " + std::to_string(*frame) + ": " : "") +
                  std::to_string(bad) +
                  " values of the mixed and graded image are not finite (NaN or infinity): "
                  "lower the gains or the grade (or check the inputs); nothing was written");
}

// One frame: read, mix, grade, display; every output written, then committed.
CompFrameReport comp_frame(const CompRecipe& recipe, const Grader& grader,
                           const fs::path& histogram_pattern, std::optional<long> frame) {
  const CompOutputs& out = recipe.outputs;
  CompFrameReport fr;
  fr.frame = frame;
  const FrameInputs inputs = read_frame_inputs(recipe, frame);
  RgbaImage canvas = mix_frame(recipe, inputs);
  FrameFiles files;
  grader.apply_grade(canvas);
  expect_finite(canvas, recipe.label, frame);
  if (!out.exr.empty()) {
    fr.exr = at_frame(out.exr, frame);
    write_graded_exr(canvas, inputs.images[recipe.layers.front().input], recipe.label,
                     files.temp_for(fr.exr), fr.exr);
  }
  RgbaImage display = std::move(canvas);
  grader.apply_display(display);
  if (!out.image.empty()) {
    fr.image = at_frame(out.image, frame);
    write_display_image(display, out, files.temp_for(fr.image), fr.image);
  }
  fr.display_histogram = display_histogram(display, LumaWeights::Rec709);
  fr.histogram = at_frame(histogram_pattern, frame);
  write_text(files.temp_for(fr.histogram), histogram_json(fr.display_histogram) + "\n",
             fr.histogram);
  if (!out.histogram_plot.empty()) {
    fr.histogram_plot = at_frame(out.histogram_plot, frame);
    write_histogram_png(fr.display_histogram, files.temp_for(fr.histogram_plot));
  }
  files.commit();
  fr.width = display.width;
  fr.height = display.height;
  return fr;
}

}  // namespace

std::vector<uint16_t> quantize_rgb(const RgbaImage& display, int bits) {
  const float maxv = bits == 16 ? 65535.f : 255.f;
  std::vector<uint16_t> out(display.pixel_count() * 3);
  for (size_t i = 0; i < display.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      float v = display.pixels[i * 4 + size_t(c)];
      if (!(v > 0.f)) v = 0.f;  // NaN and negatives
      if (v > 1.f) v = 1.f;
      out[i * 3 + size_t(c)] = uint16_t(std::lround(v * maxv));
    }
  return out;
}

CompReport run_comp(const CompRecipe& recipe, const CompProgress& progress) {
  if (recipe.inputs.empty()) throw CompError(recipe.label + ": no inputs");
  if (recipe.layers.empty()) throw CompError(recipe.label + ": no layers");
  // The OCIO processors are built once, before any pixel is read, so a
  // missing config or an unknown view fails before anything is written.
  const Grader grader(recipe.grade, recipe.display);
  const CompOutputs& out = recipe.outputs;
  const fs::path histogram_pattern =
      out.histogram.empty() ? default_histogram_path(out) : out.histogram;

  const bool sequence = !recipe.frames.empty();
  const size_t total = sequence ? recipe.frames.size() : 1;
  CompReport report;
  for (size_t fi = 0; fi < total; ++fi) {
    const std::optional<long> frame =
        sequence ? std::optional<long>(recipe.frames[fi]) : std::nullopt;
    report.frames.push_back(comp_frame(recipe, grader, histogram_pattern, frame));
    if (progress) progress(fi + 1, total);
  }
  return report;
}

}  // namespace vesper
