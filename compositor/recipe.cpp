// Composite recipe parsing and validation (recipe.h, docs/compositing.md).
#include "compositor/recipe.h"

#include <algorithm>
#include <optional>
#include <set>
#include <span>
#include <system_error>

#include <nlohmann/json.hpp>

#include "common/frame_pattern.h"
#include "common/json_parse.h"
#include "common/json_reader.h"
#include "renderer/scene/json_values.h"

namespace vesper {
namespace fs = std::filesystem;
namespace {

constexpr std::string_view kFormat = "vesper-comp/1";
constexpr std::string_view kModes[] = {"add", "over"};

// Bounds of the multipliers and the grade. Generous for any real look, but
// small enough that a float image does not overflow at the first step: a CDL
// power or saturation of 3.4e38 turned every pixel into NaN or infinity.
const Range kGain = Range::closed(-1e6, 1e6);  // layer gain and tint
const Range kCdlSlope = Range::closed(0, 1e3);
const Range kCdlOffset = Range::closed(-1e3, 1e3);
const Range kCdlPower = Range::left_open(0, 100);
const Range kCdlSaturation = Range::closed(0, 100);

fs::path resolve(const fs::path& base_dir, const std::string& s) {
  const fs::path p(s);
  return p.is_absolute() ? p : (base_dir / p).lexically_normal();
}

// Frame numbers of the files that match `pattern` (a run of '#' in the file name).
std::vector<long> glob_frames(const fs::path& pattern) {
  const std::string name = pattern.filename().string();
  const auto [pos, len] = find_frame_pattern(name);
  const std::string prefix = name.substr(0, pos), suffix = name.substr(pos + len);
  const fs::path dir = pattern.has_parent_path() ? pattern.parent_path() : fs::path(".");
  std::vector<long> frames;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string f = it->path().filename().string();
    if (f.size() <= prefix.size() + suffix.size()) continue;
    if (f.compare(0, prefix.size(), prefix) != 0) continue;
    if (f.compare(f.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
    const std::string digits = f.substr(prefix.size(), f.size() - prefix.size() - suffix.size());
    if (digits.size() > 12 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      continue;
    const long frame = std::stol(digits);
    // The canonical spelling only: frame 7 of `####` is 0007, not 07 or 00007.
    if (frame_path(pattern, frame).filename().string() != f) continue;
    if (!it->is_regular_file(ec)) continue;
    frames.push_back(frame);
  }
  std::sort(frames.begin(), frames.end());
  return frames;
}

std::string lower_extension(const fs::path& p) {
  std::string e = p.extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

fs::path parse_output_path(JsonReader& outputs, std::string_view key, const fs::path& base_dir,
                           int padding) {
  if (!outputs.has(key)) return {};
  const JsonReader node = outputs.child(key);
  const fs::path p = resolve(base_dir, node.as_string());
  const auto [pos, len] = find_frame_pattern(p.filename().string());
  if (padding > 0 && len != size_t(padding)) {
    node.fail("the inputs are a frame sequence (" + std::string(size_t(padding), '#') +
              "): expected the same " + std::string(size_t(padding), '#') +
              " pattern in the output file name, got " + describe_json(node.json()));
  }
  if (padding == 0 && len > 0) {
    node.fail("expected no frame pattern ('#') in the output: the inputs are a single frame");
  }
  if (p.has_parent_path() && p.parent_path().string().find('#') != std::string::npos)
    node.fail("a frame pattern ('#') may only appear in the file name");
  return p;
}

// A file the recipe names that must exist (a LUT, an OCIO config).
std::string existing_file(const JsonReader& node, const fs::path& base_dir, const char* what) {
  const fs::path p = resolve(base_dir, node.as_string());
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) node.fail(std::string("no such ") + what + ": " + p.string());
  return p.string();
}

// A sequence input: its frames must match the first sequence input's.
void check_sequence(const JsonReader& node, const CompInput& in, size_t pattern_length,
                    CompRecipe& recipe) {
  const std::vector<long> frames = glob_frames(in.path);
  if (frames.empty()) node.fail("no files match the frame pattern " + in.path.string());
  if (recipe.frame_padding == 0) {
    recipe.frame_padding = int(pattern_length);
    recipe.frames = frames;
    return;
  }
  if (int(pattern_length) != recipe.frame_padding)
    node.fail("expected the same frame pattern (" + std::string(size_t(recipe.frame_padding), '#') +
              ") as the other inputs");
  for (long f : recipe.frames)
    if (!std::binary_search(frames.begin(), frames.end(), f))
      node.fail("no frame " + std::to_string(f) + ": " + frame_path(in.path, f).string() +
                " does not exist (the first sequence input has it)");
}

CompInput parse_input(const JsonReader& node, const std::string& name, const fs::path& base_dir,
                      CompRecipe& recipe) {
  CompInput in;
  in.name = name;
  in.json_path = node.path();
  in.path = resolve(base_dir, node.as_string());
  const auto [pos, len] = find_frame_pattern(in.path.filename().string());
  in.sequence = len > 0;
  if (in.path.has_parent_path() && in.path.parent_path().string().find('#') != std::string::npos)
    node.fail("a frame pattern ('#') may only appear in the file name");
  if (in.sequence) {
    check_sequence(node, in, len, recipe);
  } else {
    std::error_code ec;
    if (!fs::is_regular_file(in.path, ec)) node.fail("no such file: " + in.path.string());
  }
  return in;
}

// Inputs, in document order when known (the first is every layer's default).
void parse_inputs(JsonReader inputs, const fs::path& base_dir,
                  const std::vector<std::string>& input_order, CompRecipe& recipe) {
  if (inputs.json().empty()) inputs.fail("expected at least one input, got an empty object");
  std::vector<std::string> names = input_order;
  if (names.empty())
    for (auto it = inputs.json().begin(); it != inputs.json().end(); ++it)
      names.push_back(it.key());
  for (const std::string& name : names)
    recipe.inputs.push_back(parse_input(inputs.child(name), name, base_dir, recipe));
  inputs.finish();
}

CompLayer parse_layer(JsonReader l, std::span<const std::string_view> input_names) {
  l.expect_object();
  l.allow_keys({"layer", "input", "gain", "tint", "exposure", "mode"});
  CompLayer cl;
  cl.json_path = l.key_path("layer");
  if (!l.has("layer"))
    l.fail("missing key \"layer\" (the name of a layer in the input, e.g. \"beauty\")");
  cl.op.layer = l.child("layer").as_string();
  if (l.has("input")) cl.input = l.enumeration("input", input_names);
  cl.op.gain = float(l.number("gain", 1.0, kGain));
  cl.op.tint = read_rgb(l, "tint", Rgb(1.f), kGain);
  cl.op.exposure = float(l.number("exposure", 0.0, Range::closed(-64, 64)));
  cl.op.mode = l.enumeration("mode", 0, kModes) == 0 ? BlendMode::Add : BlendMode::Over;
  l.finish();
  return cl;
}

// Layers (default: the beauty of the first input).
std::vector<CompLayer> parse_layers(const std::optional<JsonReader>& layers,
                                    const std::vector<CompInput>& inputs) {
  if (!layers) {
    CompLayer beauty;
    beauty.op.layer = "beauty";
    beauty.json_path = "/layers";
    return {beauty};
  }
  layers->expect_array();
  if (layers->size() == 0) layers->fail("expected at least one layer, got an empty array");
  std::vector<std::string_view> input_names;
  for (const auto& in : inputs) input_names.push_back(in.name);
  std::vector<CompLayer> out;
  for (size_t i = 0; i < layers->size(); ++i)
    out.push_back(parse_layer(layers->element(i), input_names));
  return out;
}

Cdl parse_cdl(JsonReader cdl) {
  cdl.expect_object();
  cdl.allow_keys({"slope", "offset", "power", "saturation"});
  Cdl c;
  c.slope = read_rgb(cdl, "slope", c.slope, kCdlSlope);
  c.offset = read_rgb(cdl, "offset", c.offset, kCdlOffset);
  c.power = read_rgb(cdl, "power", c.power, kCdlPower);
  c.saturation = float(cdl.number("saturation", 1.0, kCdlSaturation));
  return c;
}

GradeDesc parse_grade(JsonReader grade, const fs::path& base_dir) {
  grade.expect_object();
  grade.allow_keys({"exposure", "cdl", "look_lut"});
  GradeDesc g;
  g.exposure = float(grade.number("exposure", 0.0, Range::closed(-64, 64)));
  if (const auto cdl = grade.optional_child("cdl")) g.cdl = parse_cdl(*cdl);
  if (const auto lut = grade.optional_child("look_lut"))
    g.look_lut = existing_file(*lut, base_dir, "LUT file");
  return g;
}

DisplayDesc parse_display(JsonReader display, const fs::path& base_dir) {
  display.expect_object();
  display.allow_keys({"config", "display", "view"});
  DisplayDesc d;
  if (const auto config = display.optional_child("config"))
    d.config = existing_file(*config, base_dir, "OCIO config");
  if (display.has("display")) d.display = display.child("display").as_string();
  if (display.has("view")) d.view = display.child("view").as_string();
  return d;
}

// The image format from the file's extension.
ImageFormat image_format(JsonReader& outputs, const fs::path& image) {
  const std::string ext = lower_extension(image);
  if (ext == ".png") return ImageFormat::Png;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::Jpeg;
  if (ext == ".tif" || ext == ".tiff") return ImageFormat::Tiff;
  outputs.fail_key("image", "expected a .png, .jpg/.jpeg or .tif/.tiff file, got \"" +
                                image.filename().string() + "\"");
}

int parse_bit_depth(const JsonReader& b, const CompOutputs& out) {
  const int64_t bits = b.as_integer(8, 16);
  if (bits != 8 && bits != 16) b.fail("expected 8 or 16, got " + describe_json(b.json()));
  if (out.image.empty()) b.fail("bit_depth applies to the \"image\" output, which is not given");
  if (bits == 16 && out.image_format == ImageFormat::Jpeg)
    b.fail("JPEG is 8-bit only; use .png or .tif for 16 bits");
  return int(bits);
}

// Outputs are distinct files, overwrite no input, and go to existing folders.
void check_output_files(JsonReader& outputs, const CompOutputs& out,
                        const std::vector<CompInput>& inputs) {
  const std::pair<std::string_view, fs::path> files[] = {{"image", out.image},
                                                         {"exr", out.exr},
                                                         {"histogram", out.histogram},
                                                         {"histogram_plot", out.histogram_plot}};
  std::set<fs::path> seen;
  for (const auto& [key, p] : files) {
    if (p.empty()) continue;
    if (!seen.insert(p).second) outputs.fail_key(key, "the same file as another output");
    for (const auto& in : inputs)
      if (p == in.path) outputs.fail_key(key, "would overwrite the input " + in.path.string());
  }
  if (out.histogram.empty() && seen.count(default_histogram_path(out)))
    outputs.fail("the default histogram file " + default_histogram_path(out).string() +
                 " is also another output; name \"histogram\" explicitly");
  for (const auto& [key, p] : files) {
    if (p.empty() || !p.has_parent_path()) continue;
    std::error_code ec;
    if (!fs::is_directory(p.parent_path(), ec))
      outputs.fail_key(key, "the output folder " + p.parent_path().string() + " does not exist");
  }
}

CompOutputs parse_outputs(JsonReader outputs, const fs::path& base_dir, const CompRecipe& recipe) {
  outputs.allow_keys({"image", "bit_depth", "exr", "histogram", "histogram_plot"});
  CompOutputs out;
  const int pad = recipe.frame_padding;
  out.image = parse_output_path(outputs, "image", base_dir, pad);
  out.exr = parse_output_path(outputs, "exr", base_dir, pad);
  out.histogram = parse_output_path(outputs, "histogram", base_dir, pad);
  out.histogram_plot = parse_output_path(outputs, "histogram_plot", base_dir, pad);
  if (out.image.empty() && out.exr.empty())
    outputs.fail("expected an \"image\" or an \"exr\" output (or both)");
  if (!out.image.empty()) out.image_format = image_format(outputs, out.image);
  if (!out.exr.empty() && lower_extension(out.exr) != ".exr")
    outputs.fail_key("exr", "expected a .exr file, got \"" + out.exr.filename().string() + "\"");
  if (const auto bits = outputs.optional_child("bit_depth"))
    out.bit_depth = parse_bit_depth(*bits, out);
  check_output_files(outputs, out, recipe.inputs);
  return out;
}

// Throws JsonError; the public functions turn it into a CompError.
CompRecipe parse(const nlohmann::json& doc, const fs::path& base_dir, const std::string& label,
                 const std::vector<std::string>& input_order) {
  CompRecipe recipe;
  recipe.label = label;
  JsonReader root(doc, label, "");
  root.expect_object();
  root.allow_keys({"format", "inputs", "layers", "grade", "display", "outputs"});
  if (const auto format = root.optional_child("format")) format->expect_string(kFormat);
  parse_inputs(root.object("inputs"), base_dir, input_order, recipe);
  recipe.layers = parse_layers(root.optional_child("layers"), recipe.inputs);
  if (const auto grade = root.optional_child("grade")) recipe.grade = parse_grade(*grade, base_dir);
  if (const auto display = root.optional_child("display"))
    recipe.display = parse_display(*display, base_dir);
  recipe.outputs = parse_outputs(root.object("outputs"), base_dir, recipe);
  return recipe;
}

// The reader throws JsonError; every compositor error is a CompError (same text).
template <typename Parse>
auto as_comp_error(Parse parse) -> decltype(parse()) {
  try {
    return parse();
  } catch (const JsonError& e) {
    throw CompError(e.what());
  }
}

}  // namespace

fs::path default_histogram_path(const CompOutputs& outputs) {
  fs::path p = outputs.image.empty() ? outputs.exr : outputs.image;
  if (p.empty()) return {};
  return p.replace_extension(".hist.json");
}

CompRecipe parse_recipe(const nlohmann::json& doc, const fs::path& base_dir,
                        const std::string& label) {
  return as_comp_error([&] { return parse(doc, base_dir, label, {}); });
}

CompRecipe parse_recipe_text(const std::string& text, const fs::path& base_dir,
                             const std::string& label) {
  return as_comp_error([&] {
    const nlohmann::json doc = parse_json(text, label);
    // The order of "inputs" decides which is the first (the default of a layer).
    // parse_json accepted the text, so this parse is within the depth limit too.
    const auto ordered = nlohmann::ordered_json::parse(text);
    std::vector<std::string> order;
    if (ordered.is_object() && ordered.contains("inputs") && ordered["inputs"].is_object())
      for (auto it = ordered["inputs"].begin(); it != ordered["inputs"].end(); ++it)
        order.push_back(it.key());
    return parse(doc, base_dir, label, order);
  });
}

CompRecipe load_recipe(const fs::path& file) {
  const std::string text = as_comp_error([&] { return read_text_file(file, "the recipe file"); });
  const fs::path base = file.has_parent_path() ? file.parent_path() : fs::path(".");
  return parse_recipe_text(text, base, file.string());
}

}  // namespace vesper
