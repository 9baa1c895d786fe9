// Pulling layers out of a multi-layer EXR and adding them up (layer_mix.h).
#include "compositor/layer_mix.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "compositor/comp_run.h"

namespace vesper {
namespace {

// The channel indices of one layer: RGB (or XYZ for vectors, or one channel
// replicated for scalars such as depth.Z) and an optional alpha.
struct LayerChannels {
  int c[3] = {-1, -1, -1};
  int alpha = -1;
};

bool find_layer(const LayeredImage& image, const std::string& layer, LayerChannels& out) {
  const std::string prefix = layer == "beauty" ? "" : layer + ".";
  auto idx = [&](const char* suffix) { return image.channel_index(prefix + suffix); };
  out.alpha = idx("A");
  static const char* const kTriples[2][3] = {{"R", "G", "B"}, {"X", "Y", "Z"}};
  for (const auto& names : kTriples) {
    const int a = idx(names[0]), b = idx(names[1]), c = idx(names[2]);
    if (a >= 0 && b >= 0 && c >= 0) {
      out.c[0] = a;
      out.c[1] = b;
      out.c[2] = c;
      return true;
    }
  }
  if (layer == "beauty") return false;
  // A scalar layer (depth.Z, or a lone `<layer>.Y` / `.V`), shown as grey.
  int only = -1, n = 0;
  for (size_t i = 0; i < image.channels.size(); ++i) {
    const std::string& ch = image.channels[i];
    if (ch.size() > prefix.size() && ch.compare(0, prefix.size(), prefix) == 0 &&
        ch.find('.', prefix.size()) == std::string::npos && ch != prefix + "A") {
      only = int(i);
      ++n;
    }
  }
  if (n != 1) return false;
  const std::string suffix = image.channels[size_t(only)].substr(prefix.size());
  if (suffix != "Z" && suffix != "Y" && suffix != "V") return false;
  out.c[0] = out.c[1] = out.c[2] = only;
  return true;
}

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

}  // namespace

std::vector<std::string> list_layers(const LayeredImage& image) {
  std::vector<std::string> out;
  LayerChannels lc;
  if (find_layer(image, "beauty", lc)) out.push_back("beauty");
  std::set<std::string> prefixes;
  for (const std::string& ch : image.channels) {
    const size_t dot = ch.rfind('.');
    if (dot != std::string::npos && dot > 0) prefixes.insert(ch.substr(0, dot));
  }
  for (const std::string& p : prefixes)
    if (p != "beauty" && find_layer(image, p, lc)) out.push_back(p);
  return out;
}

RgbaImage extract_layer(const LayeredImage& image, const std::string& layer,
                        const std::string& source) {
  LayerChannels lc;
  if (!find_layer(image, layer, lc)) {
    throw CompError("no layer '" + layer + "' in " + source +
                    " (layers: " + join(list_layers(image)) + ")");
  }
  RgbaImage out(image.width, image.height);
  const size_t nc = image.channel_count();
  const float default_alpha = layer == "beauty" ? 1.f : 0.f;
  const size_t n = out.pixel_count();
  for (size_t i = 0; i < n; ++i) {
    const float* src = image.pixels.data() + i * nc;
    float* dst = out.pixels.data() + i * 4;
    dst[0] = src[lc.c[0]];
    dst[1] = src[lc.c[1]];
    dst[2] = src[lc.c[2]];
    dst[3] = lc.alpha >= 0 ? src[lc.alpha] : default_alpha;
  }
  return out;
}

void blend_layer(RgbaImage& canvas, const RgbaImage& layer, const LayerOp& op) {
  if (canvas.width != layer.width || canvas.height != layer.height) {
    throw CompError("layer '" + op.layer + "' is " + std::to_string(layer.width) + "x" +
                    std::to_string(layer.height) + ", the composite " +
                    std::to_string(canvas.width) + "x" + std::to_string(canvas.height));
  }
  const float e = std::exp2(op.exposure);
  const float k[3] = {op.gain * op.tint.r * e, op.gain * op.tint.g * e, op.gain * op.tint.b * e};
  const size_t n = canvas.pixel_count();
  for (size_t i = 0; i < n; ++i) {
    float* c = canvas.pixels.data() + i * 4;
    const float* l = layer.pixels.data() + i * 4;
    if (op.mode == BlendMode::Add) {
      for (int j = 0; j < 3; ++j) c[j] += l[j] * k[j];
      c[3] = std::max(c[3], l[3]);
    } else {
      const float t = 1.f - l[3];
      for (int j = 0; j < 3; ++j) c[j] = l[j] * k[j] + t * c[j];
      c[3] = l[3] + t * c[3];
    }
  }
}

RgbaImage mix_layers(const LayeredImage& image, const std::vector<LayerOp>& ops,
                     const std::string& source) {
  RgbaImage canvas(image.width, image.height);
  for (const LayerOp& op : ops) blend_layer(canvas, extract_layer(image, op.layer, source), op);
  return canvas;
}

}  // namespace vesper
