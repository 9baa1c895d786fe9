#include "regress/report_images.h"

#include <spdlog/spdlog.h>

#include "compositor/comp_run.h"
#include "compositor/grade.h"
#include "compositor/layer_mix.h"
#include "regress/difference_maps.h"
#include "renderer/output/exr_io.h"

namespace vesper::regress {

namespace fs = std::filesystem;

namespace {

std::optional<LayeredImage> read_image(const std::string& path, const char* which,
                                       std::string& problem) {
  if (path.empty()) {
    problem = std::string("no ") + which + " image";
    return std::nullopt;
  }
  try {
    return read_exr(path);
  } catch (const std::exception& e) {
    problem = std::string("cannot read the ") + which + " image: " + e.what();
    return std::nullopt;
  }
}

std::optional<RgbaImage> layer_of(const std::optional<LayeredImage>& image,
                                  const std::string& layer, const char* which,
                                  std::vector<std::string>& problems) {
  if (!image) return std::nullopt;
  try {
    return extract_layer(*image, layer, std::string("the ") + which + " render");
  } catch (const CompError& e) {
    problems.push_back(e.what());
    return std::nullopt;
  }
}

}  // namespace

SceneImages read_scene_images(const SceneResult& scene) {
  SceneImages images;
  images.golden = read_image(scene.golden_image, "golden", images.golden_problem);
  images.fresh = read_image(scene.new_image, "new", images.new_problem);
  return images;
}

ReportImages::ReportImages(fs::path report_dir, fs::path folder)
    : report_dir_(std::move(report_dir)), folder_(std::move(folder)) {
  try {
    display_ = std::make_unique<const Grader>(GradeDesc{}, DisplayDesc{});
  } catch (const CompError& e) {
    display_note_ = std::string("pictures through the plain sRGB transfer function: ") + e.what();
    spdlog::warn("regression report: {}", display_note_);
  }
  fs::create_directories(report_dir_ / folder_);
}

ReportImages::~ReportImages() = default;

RgbaImage ReportImages::to_display(RgbaImage image) const {
  if (display_) {
    display_->apply_display(image);
    return image;
  }
  for (size_t i = 0; i < image.pixels.size(); ++i)
    if (i % 4 != 3) image.pixels[i] = float(srgb_encode(image.pixels[i]));
  return image;
}

std::string ReportImages::write_png(const RgbaImage& display, const std::string& name) const {
  CompOutputs outputs;
  outputs.image_format = ImageFormat::Png;
  const fs::path file = report_dir_ / folder_ / name;
  write_display_image(display, outputs, file, file);
  return (folder_ / name).generic_string();
}

LayerPictures ReportImages::draw_layer(const SceneImages& images, const LayerResult& layer,
                                       const std::string& stem) const {
  LayerPictures out;
  const std::optional<RgbaImage> golden =
      layer_of(images.golden, layer.layer, "golden", out.problems);
  const std::optional<RgbaImage> fresh = layer_of(images.fresh, layer.layer, "new", out.problems);
  std::optional<RgbaImage> backdrop;
  if (golden) {
    out.golden = write_png(to_display(*golden), stem + ".golden.png");
    out.golden_histogram = log2_histogram(*golden, LumaWeights::Rec709);
    out.width = golden->width, out.height = golden->height;
  }
  if (fresh) {
    backdrop = to_display(*fresh);
    out.fresh = write_png(*backdrop, stem + ".new.png");
    out.new_histogram = log2_histogram(*fresh, LumaWeights::Rec709);
    out.width = fresh->width, out.height = fresh->height;
  }
  if (golden && fresh) {
    if (golden->width == fresh->width && golden->height == fresh->height) {
      const HeatMap heat = difference_heat_map(*golden, *fresh);
      out.difference = write_png(heat.image, stem + ".difference.png");
      out.difference_top = heat.top, out.difference_nonfinite = heat.nonfinite;
    } else {
      out.problems.push_back("the renders differ in size: no difference map");
    }
  }
  if (backdrop && !layer.tile_z.empty()) {
    try {
      const SignificanceMap sig = significance_map(layer, *backdrop);
      out.significance = write_png(sig.image, stem + ".significance.png");
      out.z_scale = sig.z_scale;
    } catch (const std::invalid_argument& e) {
      out.problems.push_back(e.what());
    }
  }
  return out;
}

}  // namespace vesper::regress
