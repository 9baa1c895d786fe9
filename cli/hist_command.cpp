// `vesper hist IMAGE [--ref OTHER] [--weights rec709|luminosity] [--json OUT]
// [--plot OUT.png] [--log2]`: the luminosity histogram of an image, and with
// --ref the distance to a reference and the exposure shift that matches it.
//
// PNG/JPEG/TIFF/... are display-referred: measured as they are. OpenEXR (and
// Radiance HDR) are scene-linear: the display histogram is taken after the
// OCIO display/view (default: sRGB "Standard" of $OCIO or the bundled config),
// and the log2 histogram (stops) of the scene-linear luminance is added.
// --log2 makes the log2 histogram the primary one (plot, JSON top level);
// display-referred inputs are then decoded with the sRGB inverse transfer.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/commands.h"
#include "common/atomic_file.h"
#include "compositor/grade.h"
#include "compositor/histogram.h"

namespace vesper::cli {
namespace {

namespace fs = std::filesystem;

struct Measured {
  std::string path, format;
  int width = 0, height = 0;
  bool scene_linear = false;
  Histogram display;
  std::optional<Histogram> log2;
};

Measured measure(const std::string& path, LumaWeights weights, bool want_log2,
                 const DisplayDesc& view) {
  HistogramSource src = read_histogram_source(path);
  Measured m;
  m.path = path;
  m.format = src.format;
  m.width = src.image.width;
  m.height = src.image.height;
  m.scene_linear = src.scene_linear;
  if (src.scene_linear) {
    m.log2 = log2_histogram(src.image, weights);
    RgbaImage shown = src.image;
    Grader(GradeDesc{}, view).apply_display(shown);
    m.display = display_histogram(shown, weights);
  } else {
    m.display = display_histogram(src.image, weights);
    if (want_log2) {
      RgbaImage linear = src.image;
      for (size_t i = 0; i < linear.pixel_count(); ++i)
        for (int c = 0; c < 3; ++c)
          linear.pixels[i * 4 + size_t(c)] = float(srgb_decode(linear.pixels[i * 4 + size_t(c)]));
      m.log2 = log2_histogram(linear, weights);
    }
  }
  return m;
}

std::string percentiles_line(const Histogram& h) {
  std::string s = "percentiles:";
  for (const auto& [p, v] : h.percentiles) s += fmt::format(" {:g}%: {:.4g}", p, v);
  return s + "\n";
}

std::string section(const char* title, const Histogram& h) {
  return fmt::format("{}\n{}{}", title, terminal_histogram(h), percentiles_line(h));
}

std::string comparison(const char* what, const Histogram& h, const Histogram& ref) {
  std::string s = fmt::format("reference median ({}): {:.4g}\n", what, ref.median);
  s += fmt::format("distance (Wasserstein-1, {}): {:.6g}{}\n", what, wasserstein1(h, ref),
                   h.domain == HistogramDomain::Log2 ? " stops" : "");
  try {
    s += fmt::format("matching exposure ({}): {:+.3f} stops\n", what,
                     matching_exposure_shift(h, ref));
  } catch (const CompError& e) {
    s += fmt::format("matching exposure ({}): undefined ({})\n", what, e.what());
  }
  return s;
}

void write_text_atomically(const fs::path& path, const std::string& text) {
  try {
    write_file_atomically(path, text);
  } catch (const FileWriteError& e) {
    throw CompError(e.what());
  }
}

}  // namespace

int run_hist(const HistCommandOptions& o) {
  const std::optional<LumaWeights> weights = parse_luma_weights(o.weights);
  if (!weights) {
    spdlog::error("--weights: unknown weights '{}' (expected rec709 or luminosity)", o.weights);
    return 2;
  }
  const DisplayDesc view{o.ocio_config, o.display, o.view};
  std::vector<fs::path> written;
  try {
    const Measured img = measure(o.image, *weights, o.log2, view);
    std::optional<Measured> ref;
    if (o.reference) ref = measure(*o.reference, *weights, o.log2, view);

    const Histogram& primary = o.log2 ? *img.log2 : img.display;
    const Histogram* primary_ref = nullptr;
    if (ref) primary_ref = o.log2 ? &*ref->log2 : &ref->display;

    const auto w = luma_coefficients(*weights);
    std::string out = fmt::format("{}: {}x{} {}, {}\n", img.path, img.width, img.height, img.format,
                                  img.scene_linear ? "scene-linear" : "display-referred");
    out += fmt::format("luminance: {} ({:g} R + {:g} G + {:g} B)\n", luma_weights_name(*weights),
                       w[0], w[1], w[2]);
    out += section(
        img.scene_linear
            ? fmt::format("display histogram (after OCIO {} / {}):", o.display, o.view).c_str()
            : "display histogram:",
        img.display);
    if (img.log2)
      out += section(img.scene_linear ? "log2 luminance (stops, scene-linear):"
                                      : "log2 luminance (stops, sRGB-decoded):",
                     *img.log2);
    if (ref) {
      out += fmt::format("reference {}: {}x{} {}, {}\n", ref->path, ref->width, ref->height,
                         ref->format, ref->scene_linear ? "scene-linear" : "display-referred");
      out += comparison("display", img.display, ref->display);
      if (img.log2 && ref->log2) out += comparison("log2", *img.log2, *ref->log2);
    }

    // Outputs: each written next to its target and renamed; if a later one
    // fails, the earlier ones of this run are removed again.
    try {
      if (o.plot) {
        write_histogram_png(primary, *o.plot, primary_ref);
        written.push_back(*o.plot);
      }
      if (o.json) {
        nlohmann::json j = histogram_to_json(primary, primary_ref);
        j["source"] = img.path;
        if (ref) j["reference"]["source"] = ref->path;
        if (o.log2)
          j["display"] = histogram_to_json(img.display, ref ? &ref->display : nullptr);
        else if (img.log2)
          j["log2"] = histogram_to_json(*img.log2, ref && ref->log2 ? &*ref->log2 : nullptr);
        write_text_atomically(*o.json, j.dump(2) + "\n");
        written.push_back(*o.json);
      }
    } catch (...) {
      std::error_code ec;
      for (const fs::path& p : written) fs::remove(p, ec);
      throw;
    }
    std::fwrite(out.data(), 1, out.size(), stdout);
    for (const fs::path& p : written) spdlog::info("wrote {}", p.string());
  } catch (const CompError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  return 0;
}

}  // namespace vesper::cli
