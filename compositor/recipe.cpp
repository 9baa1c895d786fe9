// Composite recipe parsing and validation (recipe.h, docs/compositing.md).
#include "compositor/recipe.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <system_error>

#include <nlohmann/json.hpp>

#include "common/json_reader.h"
#include "renderer/scene/json_values.h"

namespace vesper {
namespace fs = std::filesystem;
namespace {

constexpr std::string_view kFormat = "vesper-comp/1";
constexpr std::string_view kModes[] = {"add", "over"};

// The first run of '#' in the file name: (position, length), or length 0.
std::pair<size_t, size_t> find_pattern(const std::string& name) {
  const size_t p = name.find('#');
  if (p == std::string::npos) return {0, 0};
  size_t e = p;
  while (e < name.size() && name[e] == '#') ++e;
  return {p, e - p};
}

fs::path resolve(const fs::path& base_dir, const std::string& s) {
  const fs::path p(s);
  return p.is_absolute() ? p : (base_dir / p).lexically_normal();
}

// Frame numbers of the files that match `pattern` (a run of '#' in the file name).
std::vector<long> glob_frames(const fs::path& pattern) {
  const std::string name = pattern.filename().string();
  const auto [pos, len] = find_pattern(name);
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
  const auto [pos, len] = find_pattern(p.filename().string());
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

CompRecipe parse(const nlohmann::json& doc, const fs::path& base_dir, const std::string& label,
                 const std::vector<std::string>& input_order) {
  CompRecipe recipe;
  recipe.label = label;
  JsonReader root(doc, label, "");
  root.expect_object();
  root.allow_keys({"format", "inputs", "layers", "grade", "display", "outputs"});
  if (root.has("format")) {
    const JsonReader f = root.child("format");
    if (f.as_string() != kFormat)
      f.fail("expected \"" + std::string(kFormat) + "\", got " + describe_json(f.json()));
  }

  // Inputs, in document order when known.
  JsonReader inputs = root.object("inputs");
  if (inputs.json().empty()) inputs.fail("expected at least one input, got an empty object");
  std::vector<std::string> names = input_order;
  if (names.empty())
    for (auto it = inputs.json().begin(); it != inputs.json().end(); ++it)
      names.push_back(it.key());
  for (const std::string& name : names) {
    const JsonReader node = inputs.child(name);
    CompInput in;
    in.name = name;
    in.json_path = node.path();
    const std::string s = node.as_string();
    in.path = resolve(base_dir, s);
    const auto [pos, len] = find_pattern(in.path.filename().string());
    in.sequence = len > 0;
    if (in.path.has_parent_path() && in.path.parent_path().string().find('#') != std::string::npos)
      node.fail("a frame pattern ('#') may only appear in the file name");
    if (in.sequence) {
      const std::vector<long> frames = glob_frames(in.path);
      if (frames.empty()) node.fail("no files match the frame pattern " + in.path.string());
      if (recipe.frame_padding == 0) {
        recipe.frame_padding = int(len);
        recipe.frames = frames;
      } else {
        if (int(len) != recipe.frame_padding)
          node.fail("expected the same frame pattern (" +
                    std::string(size_t(recipe.frame_padding), '#') + ") as the other inputs");
        for (long f : recipe.frames)
          if (!std::binary_search(frames.begin(), frames.end(), f))
            node.fail("no frame " + std::to_string(f) + ": " + frame_path(in.path, f).string() +
                      " does not exist (the first sequence input has it)");
      }
    } else {
      std::error_code ec;
      if (!fs::is_regular_file(in.path, ec)) node.fail("no such file: " + in.path.string());
    }
    recipe.inputs.push_back(std::move(in));
  }
  inputs.finish();

  // Layers (default: the beauty of the first input).
  if (const auto layers = root.optional_child("layers")) {
    layers->expect_array();
    if (layers->size() == 0) layers->fail("expected at least one layer, got an empty array");
    std::vector<std::string_view> input_names;
    for (const auto& in : recipe.inputs) input_names.push_back(in.name);
    for (size_t i = 0; i < layers->size(); ++i) {
      JsonReader l = layers->element(i);
      l.expect_object();
      l.allow_keys({"layer", "input", "gain", "tint", "exposure", "mode"});
      CompLayer cl;
      cl.json_path = l.key_path("layer");
      if (l.has("layer")) {
        cl.op.layer = l.child("layer").as_string();
      } else {
        l.fail("missing key \"layer\" (the name of a layer in the input, e.g. \"beauty\")");
      }
      if (l.has("input")) cl.input = l.enumeration("input", input_names);
      cl.op.gain = float(l.number("gain", 1.0, Range::any()));
      cl.op.tint = read_rgb(l, "tint", Rgb(1.f), Range::any());
      cl.op.exposure = float(l.number("exposure", 0.0, Range::closed(-64, 64)));
      cl.op.mode = l.enumeration("mode", 0, kModes) == 0 ? BlendMode::Add : BlendMode::Over;
      l.finish();
      recipe.layers.push_back(std::move(cl));
    }
  } else {
    CompLayer cl;
    cl.op.layer = "beauty";
    cl.json_path = "/layers";
    recipe.layers.push_back(cl);
  }

  // Grade.
  if (auto grade = root.optional_child("grade")) {
    grade->expect_object();
    grade->allow_keys({"exposure", "cdl", "look_lut"});
    recipe.grade.exposure = float(grade->number("exposure", 0.0, Range::closed(-64, 64)));
    if (auto cdl = grade->optional_child("cdl")) {
      cdl->expect_object();
      cdl->allow_keys({"slope", "offset", "power", "saturation"});
      Cdl c;
      c.slope = read_rgb(*cdl, "slope", c.slope, Range::non_negative());
      c.offset = read_rgb(*cdl, "offset", c.offset, Range::any());
      c.power = read_rgb(*cdl, "power", c.power, Range::positive());
      c.saturation = float(cdl->number("saturation", 1.0, Range::non_negative()));
      recipe.grade.cdl = c;
    }
    if (grade->has("look_lut")) {
      const JsonReader lut = grade->child("look_lut");
      const fs::path p = resolve(base_dir, lut.as_string());
      std::error_code ec;
      if (!fs::is_regular_file(p, ec)) lut.fail("no such LUT file: " + p.string());
      recipe.grade.look_lut = p.string();
    }
  }

  // Display.
  if (auto display = root.optional_child("display")) {
    display->expect_object();
    display->allow_keys({"config", "display", "view"});
    if (display->has("config")) {
      const JsonReader c = display->child("config");
      const fs::path p = resolve(base_dir, c.as_string());
      std::error_code ec;
      if (!fs::is_regular_file(p, ec)) c.fail("no such OCIO config: " + p.string());
      recipe.display.config = p.string();
    }
    if (display->has("display")) recipe.display.display = display->child("display").as_string();
    if (display->has("view")) recipe.display.view = display->child("view").as_string();
  }

  // Outputs.
  JsonReader outputs = root.object("outputs");
  outputs.allow_keys({"image", "bit_depth", "exr", "histogram", "histogram_plot"});
  CompOutputs& out = recipe.outputs;
  const int pad = recipe.frame_padding;
  out.image = parse_output_path(outputs, "image", base_dir, pad);
  out.exr = parse_output_path(outputs, "exr", base_dir, pad);
  out.histogram = parse_output_path(outputs, "histogram", base_dir, pad);
  out.histogram_plot = parse_output_path(outputs, "histogram_plot", base_dir, pad);
  if (out.image.empty() && out.exr.empty())
    outputs.fail("expected an \"image\" or an \"exr\" output (or both)");
  if (!out.image.empty()) {
    const std::string ext = lower_extension(out.image);
    if (ext == ".png")
      out.image_format = ImageFormat::Png;
    else if (ext == ".jpg" || ext == ".jpeg")
      out.image_format = ImageFormat::Jpeg;
    else if (ext == ".tif" || ext == ".tiff")
      out.image_format = ImageFormat::Tiff;
    else
      outputs.fail_key("image", "expected a .png, .jpg/.jpeg or .tif/.tiff file, got \"" +
                                    out.image.filename().string() + "\"");
  }
  if (!out.exr.empty() && lower_extension(out.exr) != ".exr")
    outputs.fail_key("exr", "expected a .exr file, got \"" + out.exr.filename().string() + "\"");
  if (outputs.has("bit_depth")) {
    const JsonReader b = outputs.child("bit_depth");
    const int64_t bits = b.as_integer(8, 16);
    if (bits != 8 && bits != 16) b.fail("expected 8 or 16, got " + describe_json(b.json()));
    if (out.image.empty()) b.fail("bit_depth applies to the \"image\" output, which is not given");
    if (bits == 16 && out.image_format == ImageFormat::Jpeg)
      b.fail("JPEG is 8-bit only; use .png or .tif for 16 bits");
    out.bit_depth = int(bits);
  }
  // Distinct output files.
  std::set<fs::path> seen;
  for (const auto& [key, p] : {std::pair<std::string_view, fs::path>{"image", out.image},
                               {"exr", out.exr},
                               {"histogram", out.histogram},
                               {"histogram_plot", out.histogram_plot}}) {
    if (p.empty()) continue;
    if (!seen.insert(p).second) outputs.fail_key(key, "the same file as another output");
    for (const auto& in : recipe.inputs)
      if (p == in.path) outputs.fail_key(key, "would overwrite the input " + in.path.string());
  }
  if (out.histogram.empty() && seen.count(default_histogram_path(out)))
    outputs.fail("the default histogram file " + default_histogram_path(out).string() +
                 " is also another output; name \"histogram\" explicitly");
  for (const auto& [key, p] : {std::pair<std::string_view, fs::path>{"image", out.image},
                               {"exr", out.exr},
                               {"histogram", out.histogram},
                               {"histogram_plot", out.histogram_plot}}) {
    if (p.empty() || !p.has_parent_path()) continue;
    std::error_code ec;
    if (!fs::is_directory(p.parent_path(), ec))
      outputs.fail_key(key, "the output folder " + p.parent_path().string() + " does not exist");
  }
  return recipe;
}

}  // namespace

bool has_frame_pattern(const fs::path& path) {
  return find_pattern(path.filename().string()).second > 0;
}

fs::path frame_path(const fs::path& pattern, long frame) {
  std::string name = pattern.filename().string();
  const auto [pos, len] = find_pattern(name);
  if (len == 0) return pattern;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%0*ld", int(len), frame);
  name.replace(pos, len, buf);
  return pattern.has_parent_path() ? pattern.parent_path() / name : fs::path(name);
}

fs::path default_histogram_path(const CompOutputs& outputs) {
  fs::path p = outputs.image.empty() ? outputs.exr : outputs.image;
  if (p.empty()) return {};
  return p.replace_extension(".hist.json");
}

CompRecipe parse_recipe(const nlohmann::json& doc, const fs::path& base_dir,
                        const std::string& label) {
  try {
    return parse(doc, base_dir, label, {});
  } catch (const JsonError& e) {
    throw CompError(e.what());
  }
}

CompRecipe load_recipe(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CompError(file.string() + ": cannot read the recipe file");
  const std::string text(std::istreambuf_iterator<char>(in), {});
  nlohmann::ordered_json ordered;
  try {
    ordered = nlohmann::ordered_json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw CompError(file.string() + ": not valid JSON: " + e.what());
  }
  // The order of "inputs" decides which is the first (the default of a layer).
  std::vector<std::string> order;
  if (ordered.is_object() && ordered.contains("inputs") && ordered["inputs"].is_object())
    for (auto it = ordered["inputs"].begin(); it != ordered["inputs"].end(); ++it)
      order.push_back(it.key());
  const nlohmann::json doc = nlohmann::json::parse(text);
  const fs::path base = file.has_parent_path() ? file.parent_path() : fs::path(".");
  try {
    return parse(doc, base, file.string(), order);
  } catch (const JsonError& e) {
    throw CompError(e.what());
  }
}

}  // namespace vesper
