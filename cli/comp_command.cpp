// vesper comp: composite layered EXR passes with a recipe (docs/compositing.md)
// or from quick flags, which are turned into the same recipe document.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/progress.h"
#include "compositor/comp_run.h"
#include "compositor/recipe.h"

namespace vesper::cli {
namespace {

constexpr const char* kLabel = "vesper comp";

bool is_recipe(const std::string& path) {
  const std::filesystem::path p(path);
  std::string ext = p.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".json";
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(s);
  while (std::getline(in, part, sep)) parts.push_back(part);
  if (!s.empty() && s.back() == sep) parts.emplace_back();
  return parts;
}

double parse_number(const std::string& s, const std::string& flag) {
  try {
    size_t used = 0;
    const double v = std::stod(s, &used);
    if (used == s.size()) return v;
  } catch (const std::exception&) {
  }
  throw CompError(flag + ": expected a number, got '" + s + "'");
}

nlohmann::json parse_triple(const std::string& s, const std::string& flag) {
  const auto parts = split(s, ',');
  if (parts.size() == 1) {
    const double v = parse_number(parts[0], flag);
    return nlohmann::json::array({v, v, v});
  }
  if (parts.size() != 3)
    throw CompError(flag + ": expected r,g,b (or one number), got '" + s + "'");
  return nlohmann::json::array(
      {parse_number(parts[0], flag), parse_number(parts[1], flag), parse_number(parts[2], flag)});
}

// --layer NAME[:GAIN[:MODE]]
nlohmann::json parse_layer_flag(const std::string& spec) {
  const auto parts = split(spec, ':');
  if (parts.empty() || parts.size() > 3 || parts[0].empty())
    throw CompError("--layer: expected NAME[:GAIN[:add|over]], got '" + spec + "'");
  nlohmann::json l = {{"layer", parts[0]}};
  if (parts.size() >= 2 && !parts[1].empty()) l["gain"] = parse_number(parts[1], "--layer " + spec);
  if (parts.size() == 3) l["mode"] = parts[2];
  return l;
}

// The recipe document the quick flags stand for.
nlohmann::json flags_to_recipe(const CompCommandOptions& o) {
  nlohmann::json doc;
  doc["inputs"] = {{"frame", o.input}};
  nlohmann::json layers = nlohmann::json::array();
  if (!o.no_beauty) layers.push_back({{"layer", "beauty"}});
  for (const std::string& spec : o.layers) layers.push_back(parse_layer_flag(spec));
  if (layers.empty()) throw CompError("--no-beauty: no --layer given, nothing to composite");
  doc["layers"] = layers;

  nlohmann::json grade = nlohmann::json::object();
  if (o.exposure) grade["exposure"] = *o.exposure;
  nlohmann::json cdl = nlohmann::json::object();
  if (o.cdl_slope) cdl["slope"] = parse_triple(*o.cdl_slope, "--cdl-slope");
  if (o.cdl_offset) cdl["offset"] = parse_triple(*o.cdl_offset, "--cdl-offset");
  if (o.cdl_power) cdl["power"] = parse_triple(*o.cdl_power, "--cdl-power");
  if (o.saturation) cdl["saturation"] = *o.saturation;
  if (!cdl.empty()) grade["cdl"] = cdl;
  if (o.look) grade["look_lut"] = *o.look;
  if (!grade.empty()) doc["grade"] = grade;

  nlohmann::json display = nlohmann::json::object();
  if (o.config) display["config"] = *o.config;
  if (o.display) display["display"] = *o.display;
  if (o.view) display["view"] = *o.view;
  if (!display.empty()) doc["display"] = display;

  nlohmann::json outputs = nlohmann::json::object();
  if (o.output) outputs["image"] = *o.output;
  if (o.exr) outputs["exr"] = *o.exr;
  if (o.hist) outputs["histogram"] = *o.hist;
  if (o.hist_plot) outputs["histogram_plot"] = *o.hist_plot;
  if (o.bit_depth) outputs["bit_depth"] = *o.bit_depth;
  if (outputs.empty()) throw CompError("expected an output: -o IMAGE and/or --exr FILE");
  doc["outputs"] = outputs;
  return doc;
}

// Rewrites "vesper comp: /json/path: msg" into the flag the user typed.
std::string flag_message(const std::string& what, const CompCommandOptions& o) {
  const std::string prefix = std::string(kLabel) + ": ";
  if (what.rfind(prefix + "/", 0) != 0) return what;
  const size_t end = what.find(": ", prefix.size());
  if (end == std::string::npos) return what;
  const std::string path = what.substr(prefix.size(), end - prefix.size());
  const std::string rest = what.substr(end + 2);
  static const std::pair<const char*, const char*> kFlags[] = {
      {"/inputs/frame", "input"},
      {"/outputs/image", "-o"},
      {"/outputs/exr", "--exr"},
      {"/outputs/histogram_plot", "--hist-plot"},
      {"/outputs/histogram", "--hist"},
      {"/outputs/bit_depth", "--bit-depth"},
      {"/outputs", "outputs"},
      {"/grade/exposure", "--exposure"},
      {"/grade/cdl/slope", "--cdl-slope"},
      {"/grade/cdl/offset", "--cdl-offset"},
      {"/grade/cdl/power", "--cdl-power"},
      {"/grade/cdl/saturation", "--saturation"},
      {"/grade/look_lut", "--look"},
      {"/display/config", "--config"},
      {"/display/display", "--display"},
      {"/display/view", "--view"}};
  for (const auto& [p, flag] : kFlags)
    if (path.rfind(p, 0) == 0) return prefix + flag + ": " + rest;
  if (path.rfind("/layers/", 0) == 0) {
    const size_t i = std::stoul(path.substr(8));
    const size_t k = o.no_beauty ? i : i - 1;
    if (!o.no_beauty && i == 0) return prefix + "beauty: " + rest;
    if (k < o.layers.size()) return prefix + "--layer " + o.layers[k] + ": " + rest;
  }
  return what;
}

std::string percent(double f) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f%%", f * 100.0);
  return buf;
}

}  // namespace

int run_comp(const CompCommandOptions& o) {
  CompRecipe recipe;
  try {
    if (is_recipe(o.input)) {
      if (o.has_quick_flags())
        throw CompError(o.input +
                        ": a recipe file takes no layer/grade/display/output flags "
                        "(put them in the recipe)");
      recipe = load_recipe(o.input);
    } else {
      try {
        recipe = parse_recipe(flags_to_recipe(o), std::filesystem::current_path(), kLabel);
      } catch (const CompError& e) {
        throw CompError(flag_message(e.what(), o));
      }
      // Missing-layer messages name the flag instead of a JSON path.
      for (size_t i = 0; i < recipe.layers.size(); ++i) {
        const size_t k = o.no_beauty ? i : i - 1;
        recipe.layers[i].json_path =
            (!o.no_beauty && i == 0) ? std::string("beauty") : "--layer " + o.layers[k];
      }
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }

  CompReport report;
  try {
    Progress progress("comp");
    const bool show = !o.quiet && recipe.frames.size() > 1;
    report = vesper::run_comp(recipe, [&](size_t done, size_t total) {
      if (show) progress.update(done, total);
    });
    if (show) progress.finish();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }

  for (const CompFrameReport& f : report.frames) {
    for (const auto* p : {&f.image, &f.exr, &f.histogram, &f.histogram_plot})
      if (!p->empty()) std::printf("%s\n", p->string().c_str());
    const Histogram& h = f.display_histogram;
    if (!o.quiet) {
      std::string frame = f.frame ? "frame " + std::to_string(*f.frame) + ": " : "";
      std::fprintf(stderr,
                   "%s%dx%d, luminance (rec709, display): median %.3f, mean %.3f, clipped %s "
                   "black / %s white\n",
                   frame.c_str(), f.width, f.height, h.median, h.mean,
                   percent(h.clipped_low).c_str(), percent(h.clipped_high).c_str());
    }
  }
  return 0;
}

}  // namespace vesper::cli
