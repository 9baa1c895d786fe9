#pragma once
// Pulling layers out of a multi-layer EXR and adding them up.
#include <string>
#include <vector>

#include "compositor/rgba_image.h"
#include "renderer/math/rgb.h"
#include "renderer/output/layered_image.h"

namespace vesper {

// "beauty" for R,G,B(,A), then every prefix of `<layer>.R/G/B` channels that
// has all three (sorted). AOV layers (albedo, normal, depth...) are listed too.
std::vector<std::string> list_layers(const LayeredImage& image);

// RGB of the layer, A from `<layer>.A` (or `A` for beauty) if present, else 0
// for named layers and 1 for beauty. Throws CompError naming the layer and
// listing the available ones (`source` names the file in the message).
RgbaImage extract_layer(const LayeredImage& image, const std::string& layer,
                        const std::string& source);

enum class BlendMode { Add, Over };

struct LayerOp {
  std::string layer;
  float gain = 1.f;
  Rgb tint{1.f};
  float exposure = 0.f;  // stops: multiplies by 2^exposure
  BlendMode mode = BlendMode::Add;
};

// Applies the ops in order onto a black, transparent canvas: add = canvas +
// layer * k; over = layer * k + (1 - layer.A) * canvas (premultiplied "over"),
// k = gain * tint * 2^exposure. Output alpha: add keeps max(A), over composites A.
RgbaImage mix_layers(const LayeredImage& image, const std::vector<LayerOp>& ops,
                     const std::string& source);

}  // namespace vesper
