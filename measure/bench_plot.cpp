#include "measure/bench_plot.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>

#include "measure/plot_font.h"
#include "renderer/output/exr_io.h"

namespace vesper::measure {
namespace {

using Colour = std::array<float, 3>;
namespace IBA = OIIO::ImageBufAlgo;

constexpr int kWidth = 720, kHeight = 480;
constexpr int kLeft = 84, kRight = 150, kTop = 44, kBottom = 58;  // margins; legend on the right
const Colour kInk{0.1f, 0.1f, 0.1f}, kGrid{0.88f, 0.88f, 0.88f}, kTarget{0.8f, 0.15f, 0.15f};
const Colour kSeries[] = {
    {0.12f, 0.42f, 0.75f}, {0.95f, 0.5f, 0.08f}, {0.2f, 0.6f, 0.25f}, {0.55f, 0.3f, 0.7f}};

// A decade range [lo, hi] of log10 values covering every value given.
struct Axis {
  int lo = 0, hi = 1;
  void cover(double v) {
    if (!(v > 0) || !std::isfinite(v)) return;
    if (!used) lo = hi = int(std::floor(std::log10(v)));
    lo = std::min(lo, int(std::floor(std::log10(v))));
    hi = std::max(hi, int(std::ceil(std::log10(v))));
    used = true;
  }
  double fraction(double v) const { return (std::log10(v) - lo) / double(std::max(1, hi - lo)); }
  bool used = false;
};

struct Frame {
  Axis x, y;
  int px(double t) const {
    return kLeft + int(std::lround(x.fraction(t) * (kWidth - kLeft - kRight)));
  }
  int py(double e) const {
    return kHeight - kBottom - int(std::lround(y.fraction(e) * (kHeight - kTop - kBottom)));
  }
};

// "0.001", "1", "100" near 1; "1e-5" far from it.
std::string decade_label(int k) {
  if (k >= -3 && k <= 3) return fmt::format("{:g}", std::pow(10.0, k));
  return fmt::format("1e{}", k);
}

void thick_line(OIIO::ImageBuf& img, int x0, int y0, int x1, int y1, const Colour& c) {
  IBA::render_line(img, x0, y0, x1, y1, c);
  IBA::render_line(img, x0, y0 + 1, x1, y1 + 1, c);
  IBA::render_line(img, x0 + 1, y0, x1 + 1, y1, c);
}

// A horizontal line drawn `on` pixels, skipping `off`.
void dashed_hline(OIIO::ImageBuf& img, int x0, int x1, int y, int on, int off, const Colour& c) {
  for (int x = x0; x < x1; x += on + off) IBA::render_line(img, x, y, std::min(x1, x + on), y, c);
}

void draw_axes(OIIO::ImageBuf& img, const Frame& f, const PlotFont& font) {
  const int x0 = kLeft, x1 = kWidth - kRight, y0 = kTop, y1 = kHeight - kBottom;
  for (int k = f.x.lo; k <= f.x.hi; ++k) {
    const int x = f.px(std::pow(10.0, k));
    IBA::render_line(img, x, y0, x, y1, kGrid);
    IBA::render_line(img, x, y1, x, y1 + 5, kInk);
    font.draw(img, x, y1 + 20, decade_label(k), 14, kInk, TextAlign::Center);
    for (int m = 2; m < 10 && k < f.x.hi; ++m)  // minor ticks: 2..9 times the decade
      IBA::render_line(img, f.px(m * std::pow(10.0, k)), y1, f.px(m * std::pow(10.0, k)), y1 + 2,
                       kInk);
  }
  for (int k = f.y.lo; k <= f.y.hi; ++k) {
    const int y = f.py(std::pow(10.0, k));
    IBA::render_line(img, x0, y, x1, y, kGrid);
    IBA::render_line(img, x0 - 5, y, x0, y, kInk);
    font.draw(img, x0 - 8, y + 5, decade_label(k), 14, kInk, TextAlign::Right);
    for (int m = 2; m < 10 && k < f.y.hi; ++m)
      IBA::render_line(img, x0 - 2, f.py(m * std::pow(10.0, k)), x0, f.py(m * std::pow(10.0, k)),
                       kInk);
  }
  IBA::render_box(img, x0, y0, x1, y1, kInk, false);
  font.draw(img, (x0 + x1) / 2, kHeight - 14, "render time (s)", 15, kInk, TextAlign::Center);
  font.draw(img, 8, y0 - 12, "relMSE", 15, kInk);
}

void draw_targets(OIIO::ImageBuf& img, const Frame& f, const std::vector<double>& targets,
                  const PlotFont& font) {
  for (double t : targets) {
    const int y = f.py(t);
    dashed_hline(img, kLeft, kWidth - kRight, y, 8, 5, kTarget);
    font.draw(img, kWidth - kRight - 4, y - 4, fmt::format("{:g}", t), 13, kTarget,
              TextAlign::Right);
  }
}

void draw_run(OIIO::ImageBuf& img, const Frame& f, const RendererRun& run, const Colour& c,
              int legend_row, const PlotFont& font) {
  for (size_t i = 1; i < run.curve.size(); ++i)
    thick_line(img, f.px(run.curve[i - 1].render_seconds), f.py(run.curve[i - 1].relmse),
               f.px(run.curve[i].render_seconds), f.py(run.curve[i].relmse), c);
  for (const Measurement& m : run.curve) {
    const int x = f.px(m.render_seconds), y = f.py(m.relmse);
    IBA::render_box(img, x - 3, y - 3, x + 3, y + 3, c, true);
  }
  if (run.noise_floor > 0)
    dashed_hline(img, kLeft, kWidth - kRight, f.py(run.noise_floor), 2, 4, c);
  const int lx = kWidth - kRight + 14, ly = kTop + 10 + 22 * legend_row;
  IBA::render_box(img, lx, ly - 4, lx + 14, ly + 4, c, true);
  font.draw(img, lx + 20, ly + 5, run.renderer, 14, kInk);
}

void draw_legend_notes(OIIO::ImageBuf& img, int rows, const PlotFont& font) {
  const int lx = kWidth - kRight + 14, ly = kTop + 10 + 22 * rows;
  dashed_hline(img, lx, lx + 14, ly, 8, 5, kTarget);
  font.draw(img, lx + 20, ly + 5, "target", 13, kInk);
  dashed_hline(img, lx, lx + 14, ly + 22, 2, 4, kInk);
  font.draw(img, lx + 20, ly + 27, "ref. noise", 13, kInk);
}

Frame frame_for(const SceneResult& s, const std::vector<double>& targets) {
  Frame f;
  for (const RendererRun& r : s.runs) {
    for (const Measurement& m : r.curve) {
      f.x.cover(m.render_seconds);
      f.y.cover(m.relmse);
    }
    f.y.cover(r.noise_floor);
  }
  for (double t : targets) f.y.cover(t);
  if (!f.x.used) f.x.cover(1);
  if (f.x.hi == f.x.lo) ++f.x.hi;
  if (f.y.hi == f.y.lo) ++f.y.hi;
  return f;
}

void write_png_atomically(const OIIO::ImageBuf& img, const std::filesystem::path& path) {
  const std::filesystem::path tmp =
      path.parent_path() / ("." + path.filename().string() + ".tmp.png");
  if (!img.write(tmp.string(), OIIO::TypeDesc::UINT8)) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw ImageIoError("cannot write " + path.string() + ": " + img.geterror());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw ImageIoError("cannot write " + path.string() + ": " + ec.message());
  }
}

}  // namespace

void write_plot_png(const SceneResult& scene, const std::vector<double>& targets,
                    const std::filesystem::path& path) {
  OIIO::ImageBuf img(OIIO::ImageSpec(kWidth, kHeight, 3, OIIO::TypeDesc::FLOAT));
  IBA::fill(img, {1.0f, 1.0f, 1.0f});
  const PlotFont font;
  const Frame f = frame_for(scene, targets);
  draw_axes(img, f, font);
  draw_targets(img, f, targets, font);
  int row = 0;
  for (const RendererRun& run : scene.runs)
    draw_run(img, f, run, kSeries[size_t(row) % std::size(kSeries)], row, font), ++row;
  draw_legend_notes(img, row, font);
  font.draw(img, kLeft, 26,
            fmt::format("{} ({}, {}x{}, reference {} spp)", scene.name, scene.kind, scene.width,
                        scene.height, scene.reference_spp),
            17, kInk);
  write_png_atomically(img, path);
}

}  // namespace vesper::measure
