// Grading and display transforms through OpenColorIO (the only OCIO
// translation unit). See compositor/README.md for the order of operations.
#include "compositor/grade.h"

#include <OpenColorIO/OpenColorIO.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <utility>

namespace OCIO = OCIO_NAMESPACE;

namespace vesper {

namespace fs = std::filesystem;

std::string bundled_ocio_config() {
  return std::string(VESPER_SOURCE_DIR) + "/configs/ocio/config.ocio";
}

struct Grader::Impl {
  std::string config_path;
  OCIO::ConstConfigRcPtr config;
  OCIO::ConstCPUProcessorRcPtr grade;    // null when the grade is an identity
  OCIO::ConstCPUProcessorRcPtr display;  // null when the view is a no-op
};

namespace {

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out += ", ";
    out += "'" + n + "'";
  }
  return out;
}

std::string choose_config_path(const DisplayDesc& d) {
  if (!d.config.empty()) return d.config;
  if (const char* env = std::getenv("OCIO"); env && *env) return env;
  return bundled_ocio_config();
}

OCIO::ConstConfigRcPtr load_config(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw CompError("OCIO config not found: " + path);
  try {
    auto config = OCIO::Config::CreateFromFile(path.c_str());
    config->validate();
    return config;
  } catch (const OCIO::Exception& e) {
    throw CompError("OCIO config " + path + " is invalid: " + e.what());
  }
}

std::vector<std::string> display_names(const OCIO::Config& config) {
  std::vector<std::string> out;
  for (int i = 0; i < config.getNumDisplays(); ++i) out.emplace_back(config.getDisplay(i));
  return out;
}

std::vector<std::string> view_names(const OCIO::Config& config, const std::string& display) {
  std::vector<std::string> out;
  for (int i = 0; i < config.getNumViews(display.c_str()); ++i)
    out.emplace_back(config.getView(display.c_str(), i));
  return out;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  for (const auto& n : names)
    if (n == name) return true;
  return false;
}

// Exposure (2^e scale), ASC CDL without clamping, then the LUT look, all in
// the scene_linear colour space the image is already in.
OCIO::ConstCPUProcessorRcPtr make_grade(const OCIO::ConstConfigRcPtr& config,
                                        const std::string& config_path, const GradeDesc& grade) {
  auto group = OCIO::GroupTransform::Create();
  if (grade.exposure != 0.f) {
    if (!std::isfinite(grade.exposure)) throw CompError("grade exposure is not finite");
    const double k = std::exp2(double(grade.exposure));
    double m44[16], offset4[4] = {0, 0, 0, 0};
    const double scale4[4] = {k, k, k, 1.0};
    OCIO::MatrixTransform::Scale(m44, offset4, scale4);
    auto m = OCIO::MatrixTransform::Create();
    m->setMatrix(m44);
    m->setOffset(offset4);
    group->appendTransform(m);
  }
  if (grade.cdl) {
    const Cdl& c = *grade.cdl;
    auto cdl = OCIO::CDLTransform::Create();
    const double slope[3] = {c.slope.r, c.slope.g, c.slope.b};
    const double offset[3] = {c.offset.r, c.offset.g, c.offset.b};
    const double power[3] = {c.power.r, c.power.g, c.power.b};
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(slope[i]) || !std::isfinite(offset[i]) || !(power[i] > 0.0) ||
          !std::isfinite(power[i]))
        throw CompError("grade cdl: slope and offset must be finite and power > 0");
    if (!std::isfinite(c.saturation) || c.saturation < 0.f)
      throw CompError("grade cdl: saturation must be >= 0");
    cdl->setStyle(OCIO::CDL_NO_CLAMP);
    cdl->setSlope(slope);
    cdl->setOffset(offset);
    cdl->setPower(power);
    cdl->setSat(c.saturation);
    group->appendTransform(cdl);
  }
  if (!grade.look_lut.empty()) {
    std::error_code ec;
    const fs::path lut = fs::absolute(grade.look_lut, ec);
    std::ifstream probe(lut, std::ios::binary);
    if (ec || !fs::is_regular_file(lut, ec) || !probe)
      throw CompError("look LUT not found or unreadable: " + grade.look_lut);
    auto ft = OCIO::FileTransform::Create();
    ft->setSrc(lut.string().c_str());
    ft->setInterpolation(OCIO::INTERP_BEST);
    group->appendTransform(ft);
  }
  if (group->getNumTransforms() == 0) return nullptr;
  try {
    // Lossless optimisation: the CDL power is evaluated exactly (the default
    // level would use OCIO's fast pow approximation).
    return config->getProcessor(group)->getOptimizedCPUProcessor(OCIO::OPTIMIZATION_LOSSLESS);
  } catch (const OCIO::Exception& e) {
    if (!grade.look_lut.empty())
      throw CompError("look LUT " + grade.look_lut + " could not be loaded: " + e.what());
    throw CompError("grade with OCIO config " + config_path + " failed: " + e.what());
  }
}

void run_processor(const OCIO::ConstCPUProcessorRcPtr& proc, RgbaImage& image) {
  if (!proc || image.width <= 0 || image.height <= 0) return;
  if (image.pixels.size() != image.pixel_count() * 4)
    throw CompError("RgbaImage: pixel buffer size does not match width x height x 4");
  const long w = image.width;
  // OCIO's CPU processors are thread-safe; rows are processed in blocks.
  tbb::parallel_for(tbb::blocked_range<int>(0, image.height, 16),
                    [&](const tbb::blocked_range<int>& rows) {
                      float* start = image.pixels.data() + size_t(rows.begin()) * size_t(w) * 4;
                      OCIO::PackedImageDesc desc(start, w, long(rows.end() - rows.begin()), 4);
                      proc->apply(desc);
                    });
}

}  // namespace

Grader::Grader(const GradeDesc& grade, const DisplayDesc& display)
    : impl_(std::make_unique<Impl>()) {
  impl_->config_path = choose_config_path(display);
  impl_->config = load_config(impl_->config_path);
  const auto& config = impl_->config;

  const auto displays = display_names(*config);
  if (!contains(displays, display.display))
    throw CompError("OCIO config " + impl_->config_path + ": unknown display '" + display.display +
                    "' (displays: " + join(displays) + ")");
  const auto views = view_names(*config, display.display);
  if (!contains(views, display.view))
    throw CompError("OCIO config " + impl_->config_path + ": unknown view '" + display.view +
                    "' for display '" + display.display + "' (views: " + join(views) + ")");

  auto scene_linear = config->getColorSpace(OCIO::ROLE_SCENE_LINEAR);
  if (!scene_linear)
    throw CompError("OCIO config " + impl_->config_path +
                    " has no scene_linear role (needed as the compositing space)");

  impl_->grade = make_grade(config, impl_->config_path, grade);

  try {
    auto dvt = OCIO::DisplayViewTransform::Create();
    dvt->setSrc(scene_linear->getName());
    dvt->setDisplay(display.display.c_str());
    dvt->setView(display.view.c_str());
    auto proc = config->getProcessor(dvt);
    if (!proc->isNoOp())
      impl_->display = proc->getOptimizedCPUProcessor(OCIO::OPTIMIZATION_DEFAULT);
  } catch (const OCIO::Exception& e) {
    throw CompError("OCIO config " + impl_->config_path + ": display '" + display.display +
                    "' view '" + display.view + "' failed: " + e.what());
  }
}

Grader::~Grader() = default;
Grader::Grader(Grader&&) noexcept = default;
Grader& Grader::operator=(Grader&&) noexcept = default;

void Grader::apply_grade(RgbaImage& image) const { run_processor(impl_->grade, image); }

void Grader::apply_display(RgbaImage& image) const { run_processor(impl_->display, image); }

const std::string& Grader::config_path() const { return impl_->config_path; }

std::vector<std::string> Grader::displays() const { return display_names(*impl_->config); }

std::vector<std::string> Grader::views(const std::string& display) const {
  return view_names(*impl_->config, display);
}

}  // namespace vesper
