#pragma once
// Colour through OpenColorIO: exposure and ASC CDL in scene-linear (no
// clamping), an optional LUT look (FileTransform), then a display/view
// transform. OCIO headers stay in grade.cpp.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compositor/rgba_image.h"
#include "renderer/math/rgb.h"

namespace vesper {

struct Cdl {
  Rgb slope{1.f}, offset{0.f}, power{1.f};
  float saturation = 1.f;
};

struct GradeDesc {
  float exposure = 0.f;    // stops
  std::optional<Cdl> cdl;  // ASC CDL, style "no clamp"
  std::string look_lut;    // path to a LUT file (.cube, .spi3d, ...), empty = none
};

struct DisplayDesc {
  std::string
      config;  // path to config.ocio; empty = $OCIO, else the repository's configs/ocio/config.ocio
  std::string display = "sRGB";
  std::string view = "Standard";
};

// The repository's config (configs/ocio/config.ocio).
std::string bundled_ocio_config();

class Grader {
 public:
  // Throws CompError: missing/invalid config (names the path), unknown display
  // or view (lists the available ones), unreadable LUT (names the path).
  Grader(const GradeDesc& grade, const DisplayDesc& display);
  ~Grader();
  Grader(Grader&&) noexcept;
  Grader& operator=(Grader&&) noexcept;

  void apply_grade(RgbaImage& image) const;    // scene-linear -> graded scene-linear
  void apply_display(RgbaImage& image) const;  // graded scene-linear -> display-referred
  const std::string& config_path() const;
  std::vector<std::string> displays() const;
  std::vector<std::string> views(const std::string& display) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace vesper
