#pragma once
// The pictures of the HTML report, written as 8-bit PNGs beside the page:
// per scene and layer the golden and the new render through the display
// transform (OCIO, as `vesper render -o x.png`), the difference heat map and
// the significance map, plus both luminosity histograms for the SVG overlay.
// A picture that cannot be drawn (an error scene's missing EXR, a layer only
// one side has) is left out with the reason: the report never fails on it.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "compositor/histogram.h"
#include "regress/regress_result.h"
#include "renderer/output/layered_image.h"

namespace vesper {
class Grader;
}

namespace vesper::regress {

// A scene's two EXRs as read (or why not).
struct SceneImages {
  std::optional<LayeredImage> golden, fresh;
  std::string golden_problem, new_problem;  // empty when read
};
SceneImages read_scene_images(const SceneResult& scene);

struct LayerPictures {
  // Paths relative to the report folder ('/'-separated); empty = not drawn.
  std::string golden, fresh, difference, significance;
  std::vector<std::string> problems;  // why a picture is missing, one line each
  int width = 0, height = 0;          // of the new render's layer (else the golden's)
  double difference_top = 0;          // |luminance difference| at the top of the heat-map ramp
  uint64_t difference_nonfinite = 0;  // pixels drawn magenta
  double z_scale = 0;                 // |Z| at the ends of the significance ramp
  std::optional<Histogram> golden_histogram, new_histogram;  // log2 stops
};

class ReportImages {
 public:
  // Pictures go to `report_dir / folder`, named in the page as `folder/...`.
  // The display transform is OCIO's default display and view; without a
  // usable OCIO config the sRGB transfer function stands in (and says so).
  ReportImages(std::filesystem::path report_dir, std::filesystem::path folder);
  ~ReportImages();

  // `stem` a file-name-safe prefix unique to the scene and layer.
  LayerPictures draw_layer(const SceneImages& images, const LayerResult& layer,
                           const std::string& stem) const;
  // Empty, or why the display transform is the sRGB stand-in.
  const std::string& display_note() const { return display_note_; }

 private:
  std::string write_png(const RgbaImage& display, const std::string& name) const;
  RgbaImage to_display(RgbaImage scene_linear) const;

  std::filesystem::path report_dir_, folder_;
  std::unique_ptr<const Grader> display_;
  std::string display_note_;
};

}  // namespace vesper::regress
