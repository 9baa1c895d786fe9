#pragma once
// Running a composite recipe: for every frame, read the EXR(s), mix the layers,
// grade (OCIO), write the scene-linear EXR, apply the display/view, write the
// 8/16-bit image and the luminosity histogram (JSON + optional PNG plot).
// Every output of a frame is written under a temporary name and renamed only
// once the whole frame has succeeded: a failed frame leaves nothing behind.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <vector>

#include "compositor/histogram.h"
#include "compositor/layer_mix.h"
#include "compositor/recipe.h"

namespace vesper {

struct CompFrameReport {
  std::optional<long> frame;                                    // for sequences
  std::filesystem::path image, exr, histogram, histogram_plot;  // written (empty = not asked)
  Histogram display_histogram;  // Rec.709 luminance of the display-referred composite
  int width = 0, height = 0;
};

struct CompReport {
  std::vector<CompFrameReport> frames;
};

// (frames done, frames total), called after every frame.
using CompProgress = std::function<void(size_t, size_t)>;

// Throws CompError (naming the file, JSON path, layer or view) on the first
// failing frame; outputs of frames already finished stay.
CompReport run_comp(const CompRecipe& recipe, const CompProgress& progress = {});

// One layer op onto a canvas, exactly as mix_layers applies it (add or
// premultiplied over). Throws CompError if the sizes differ.
void blend_layer(RgbaImage& canvas, const RgbaImage& layer, const LayerOp& op);

// Writes a display-referred image as run_comp does (PNG, JPEG or TIFF by
// outputs.image_format, outputs.bit_depth bits) to `file`; a CompError names
// `final_path` (the name `file` will be renamed to).
void write_display_image(const RgbaImage& display, const CompOutputs& outputs,
                         const std::filesystem::path& file,
                         const std::filesystem::path& final_path);

// Float [0,1] to 8- or 16-bit with rounding; NaN and negatives to 0, >1 clamps.
// Returns channels R,G,B (interleaved, `bits` = 8: uint8 bytes, 16: uint16 values).
std::vector<uint16_t> quantize_rgb(const RgbaImage& display, int bits);

}  // namespace vesper
