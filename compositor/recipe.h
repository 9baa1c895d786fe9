#pragma once
// The composite recipe (JSON, docs/compositing.md): inputs (EXRs or `####`
// frame sequences), layer ops, grade, display/view, outputs. Loading
// validates everything that can be checked without reading pixels; every
// error is a CompError "<recipe>: <json path>: <message>".
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "compositor/grade.h"
#include "compositor/layer_mix.h"

namespace vesper {

struct CompInput {
  std::string name;            // key in "inputs"
  std::filesystem::path path;  // resolved; may hold a `#...#` pattern
  bool sequence = false;       // the path holds a run of '#'
  std::string json_path;       // "/inputs/<name>", for messages
};

struct CompLayer {
  LayerOp op;
  size_t input = 0;       // index into CompRecipe::inputs
  std::string json_path;  // "/layers/<i>/layer", for messages
};

enum class ImageFormat { Png, Jpeg, Tiff };

struct CompOutputs {
  std::filesystem::path image;  // display-referred 8/16-bit image; empty = none
  ImageFormat image_format = ImageFormat::Png;
  int bit_depth = 8;                     // 8 or 16 (JPEG: 8)
  std::filesystem::path exr;             // graded scene-linear float EXR; empty = none
  std::filesystem::path histogram;       // JSON; empty = `<image or exr stem>.hist.json`
  std::filesystem::path histogram_plot;  // PNG plot; empty = none
};

struct CompRecipe {
  std::string label;  // how messages name the recipe (its file, or "command line")
  std::vector<CompInput> inputs;
  std::vector<CompLayer> layers;
  GradeDesc grade;
  DisplayDesc display;
  CompOutputs outputs;
  // Frame numbers of a sequence (sorted), found by globbing the first
  // sequence input; empty for a single frame.
  std::vector<long> frames;
  int frame_padding = 0;  // number of '#' in the pattern
};

// Reads and validates a recipe; relative paths resolve against the file's folder.
CompRecipe load_recipe(const std::filesystem::path& file);
// The same from the recipe's text (what load_recipe reads): relative paths
// resolve against `base_dir`, messages name `label`.
CompRecipe parse_recipe_text(const std::string& text, const std::filesystem::path& base_dir,
                             const std::string& label);
// The same from a parsed document: relative paths resolve against `base_dir`,
// messages name `label`.
CompRecipe parse_recipe(const nlohmann::json& doc, const std::filesystem::path& base_dir,
                        const std::string& label);

// The histogram JSON written when the recipe names none: `<image stem>.hist.json`
// next to the image (or the EXR when there is no image).
std::filesystem::path default_histogram_path(const CompOutputs& outputs);

}  // namespace vesper
