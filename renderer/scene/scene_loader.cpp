// load_scene / parse_scene: the top level of `vesper-scene/1` plus camera,
// film, render and materials. Shapes, lights, media, layers and transforms have their own files.
#include "renderer/scene/scene_loader.h"

#include <climits>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>

#include <nlohmann/json.hpp>

#include "renderer/scene/json_reader.h"
#include "renderer/scene/scene_parse.h"

namespace vesper {
namespace {

constexpr std::string_view kFormat = "vesper-scene/1";
constexpr std::string_view kCameraTypes[] = {"perspective"};
constexpr std::string_view kFilters[] = {"box", "gaussian"};
constexpr std::string_view kMaterialTypes[] = {"diffuse", "conductor", "dielectric", "principled"};

// FNV-1a 64: the hash only has to tell scenes apart for caching and image
// metadata, not resist an adversary, so no cryptographic hash is needed here
// (the farm addresses blobs by sha256 itself).
struct Fnv1a64 {
  uint64_t h = 0xcbf29ce484222325ull;
  void add(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  }
  void add_sized(const std::string& s) {  // length-prefixed so concatenations stay distinct
    const uint64_t n = s.size();
    add(&n, sizeof n);
    add(s.data(), s.size());
  }
  std::string hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
  }
};

std::string read_file(const std::filesystem::path& path, bool& ok) {
  std::ifstream in(path, std::ios::binary);
  ok = bool(in);
  return ok ? std::string(std::istreambuf_iterator<char>(in), {}) : std::string();
}

CameraDesc parse_camera(JsonReader node) {
  node.expect_object();
  node.enumeration("type", kCameraTypes);
  node.allow_keys({"type", "from", "to", "up", "fov", "aperture", "focus_distance"});
  CameraDesc cam;
  cam.from = node.vec3("from");
  cam.to = node.vec3("to");
  cam.up = node.vec3("up");
  cam.fov_degrees = node.number("fov", Range::open(0, 180));
  cam.aperture = node.number("aperture", 0.0, Range::non_negative());
  const Vec3d forward = cam.to - cam.from;
  if (!(max_abs_component(forward) > 0)) {
    node.fail_key("to", "expected 'to' to differ from 'from'");
  }
  const Vec3d f = normalize(forward / max_abs_component(forward));
  const double up_scale = max_abs_component(cam.up);
  if (!(up_scale > 0) || length(cross(f, normalize(cam.up / up_scale))) < 1e-6) {
    node.fail_key("up", "expected an up vector not parallel to the view direction (to - from)");
  }
  cam.focus_distance = node.number("focus_distance", length(forward), Range::positive());
  return cam;
}

FilmDesc parse_film(JsonReader node) {
  node.expect_object();
  node.allow_keys({"width", "height", "filter"});
  FilmDesc film;
  film.width = int(node.integer("width", 1, 65536));
  film.height = int(node.integer("height", 1, 65536));
  film.filter =
      node.enumeration("filter", 0, kFilters) == 0 ? FilterType::Box : FilterType::Gaussian;
  return film;
}

RenderDesc parse_render(JsonReader node) {
  node.expect_object();
  node.allow_keys({"spp", "max_depth", "seed", "aovs"});
  RenderDesc render;
  render.spp = int(node.integer("spp", 1, INT_MAX));
  render.max_depth = int(node.integer("max_depth", 8, 1, INT_MAX));
  if (const auto seed = node.optional_child("seed")) render.seed = seed->as_uint64();
  if (const auto aovs = node.optional_child("aovs")) {
    aovs->expect_array();
    for (size_t i = 0; i < aovs->size(); ++i) {
      const JsonReader e = aovs->element(i);
      const Aov aov = static_cast<Aov>(e.as_enum(kAovNames));
      for (size_t j = 0; j < render.aovs.size(); ++j) {
        if (render.aovs[j] == aov) {
          e.fail("duplicate AOV " + e.json().dump() + " (already at " +
                 json_pointer_append(aovs->path(), j) + ")");
        }
      }
      render.aovs.push_back(aov);
    }
  }
  return render;
}

MaterialDesc parse_material(JsonReader node) {
  node.expect_object();
  const Range unit = Range::closed(0, 1);
  switch (node.enumeration("type", kMaterialTypes)) {
    case 0: {
      node.allow_keys({"type", "albedo"});
      DiffuseMaterialDesc m;
      m.albedo = node.rgb("albedo", m.albedo, unit);
      return m;
    }
    case 1: {
      node.allow_keys({"type", "roughness", "eta", "k"});
      ConductorMaterialDesc m;
      m.roughness = node.number("roughness", m.roughness, unit);
      m.eta = node.rgb("eta", m.eta, Range::positive());
      m.k = node.rgb("k", m.k, Range::non_negative());
      return m;
    }
    case 2: {
      node.allow_keys({"type", "ior", "roughness"});
      DielectricMaterialDesc m;
      m.ior = node.number("ior", m.ior, Range::positive());
      m.roughness = node.number("roughness", m.roughness, unit);
      return m;
    }
    default: {
      node.allow_keys({"type", "base_color", "metallic", "roughness"});
      PrincipledMaterialDesc m;
      m.base_color = node.rgb("base_color", m.base_color, unit);
      m.metallic = node.number("metallic", m.metallic, unit);
      m.roughness = node.number("roughness", m.roughness, unit);
      return m;
    }
  }
}

// nlohmann keeps the last of duplicate keys silently; a duplicated key in a
// scene is almost always a mistake, so the parse callback reports it.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(std::string file) : file_(std::move(file)) {}
  bool operator()(int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start:
        stack_.push_back({false, 0, {}, {}});
        break;
      case E::array_start:
        stack_.push_back({true, 0, {}, {}});
        break;
      case E::key: {
        Frame& top = stack_.back();
        top.key = parsed.get<std::string>();
        if (!top.keys.insert(top.key).second) {
          throw SceneError(file_, path(), "duplicate key '" + top.key + "'");
        }
        break;
      }
      case E::object_end:
      case E::array_end:
        stack_.pop_back();
        [[fallthrough]];
      case E::value:
        if (!stack_.empty() && stack_.back().is_array) ++stack_.back().index;
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_array;
    size_t index;
    std::string key;
    std::set<std::string> keys;
  };
  std::string path() const {
    std::string p;
    for (const Frame& f : stack_) {
      p = f.is_array ? json_pointer_append(p, f.index) : json_pointer_append(p, f.key);
    }
    return p;
  }
  std::string file_;
  std::vector<Frame> stack_;
};

// nlohmann reports a byte offset; people need line and column.
std::string at_line_column(const std::string& text, size_t offset) {
  const size_t end = std::min(offset, text.size());
  size_t line = 1, line_start = 0;
  for (size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') ++line, line_start = i + 1;
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(end - line_start + 1);
}

// nlohmann's what() minus its "[json.exception.x.N] ... column C: " prefix.
std::string nlohmann_detail(const nlohmann::json::exception& e) {
  std::string detail = e.what();
  if (const size_t bracket = detail.find("] "); bracket != std::string::npos) {
    detail = detail.substr(bracket + 2);
  }
  if (detail.rfind("parse error", 0) == 0) {
    if (const size_t colon = detail.find(": "); colon != std::string::npos) {
      detail = detail.substr(colon + 2);
    }
  }
  return detail;
}

}  // namespace

SceneError::SceneError(std::string file, std::string json_path, std::string message)
    : std::runtime_error(file + ": " + (json_path.empty() ? "" : json_path + ": ") + message),
      file_(std::move(file)),
      json_path_(std::move(json_path)),
      message_(std::move(message)) {}

std::filesystem::path SceneParseContext::resolve(const std::string& relative) const {
  const std::filesystem::path p(relative);
  return p.is_absolute() ? p : base_dir / p;
}

uint32_t SceneParseContext::material(JsonReader& node, std::string_view key) const {
  const std::string name = node.child(key).as_string();
  for (size_t i = 0; i < material_names.size(); ++i) {
    if (material_names[i] == name) return uint32_t(i);
  }
  std::string known;
  for (const std::string& n : material_names) known += (known.empty() ? "" : ", ") + n;
  node.fail_key(key, "unknown material \"" + name +
                         "\" (known materials: " + (known.empty() ? "none" : known) + ")");
}

SceneDescription load_scene(const std::filesystem::path& file) {
  bool ok = false;
  const std::string text = read_file(file, ok);
  if (!ok) throw SceneError(file.string(), "", "cannot open the scene file");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text, DuplicateKeyCheck(file.string()));
  } catch (const nlohmann::json::parse_error& e) {
    throw SceneError(file.string(), "",
                     "invalid JSON at " + at_line_column(text, e.byte > 0 ? e.byte - 1 : 0) + ": " +
                         nlohmann_detail(e));
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond the double range (1e999) carries no position; find its text.
    std::string where = "invalid JSON";
    const std::string what = e.what();
    const size_t q = what.find('\'');
    if (q != std::string::npos && what.back() == '\'') {
      const size_t at = text.find(what.substr(q + 1, what.size() - q - 2));
      if (at != std::string::npos) where += " at " + at_line_column(text, at);
    }
    throw SceneError(file.string(), "",
                     where + ": " + nlohmann_detail(e) + " (numbers must be finite doubles)");
  }
  return parse_scene(doc, file);
}

SceneDescription parse_scene(const nlohmann::json& doc, const std::filesystem::path& file) {
  SceneParseContext ctx;
  ctx.file = file.string();
  ctx.base_dir = file.parent_path();
  JsonReader root(doc, ctx.file, "");
  root.expect_object();

  // The version decides what the rest means, so it is checked before anything else.
  const JsonReader format = root.child("format");
  if (!format.json().is_string() || format.json().get<std::string>() != kFormat) {
    format.fail("expected \"" + std::string(kFormat) + "\", got " + describe_json(format.json()));
  }
  root.allow_keys(
      {"format", "camera", "film", "render", "materials", "shapes", "lights", "media", "layers"});

  SceneDescription scene;
  scene.file = file;
  scene.camera = parse_camera(root.object("camera"));
  scene.film = parse_film(root.object("film"));
  scene.render = parse_render(root.object("render"));

  const JsonReader materials = root.object("materials");
  for (const auto& [name, value] : materials.json().items()) {
    JsonReader m(value, ctx.file, materials.key_path(name));
    if (name.empty()) m.fail("expected a non-empty material name");
    scene.materials.push_back(parse_material(m));
    scene.material_names.push_back(name);
  }
  ctx.material_names = scene.material_names;

  const JsonReader shapes = root.array("shapes");
  for (size_t i = 0; i < shapes.size(); ++i) {
    scene.shapes.push_back(parse_shape(shapes.element(i), ctx));
  }

  if (const auto lights = root.optional_child("lights")) {
    lights->expect_array();
    std::optional<size_t> environment;
    for (size_t i = 0; i < lights->size(); ++i) {
      // Checked before parsing so a second environment image is not even loaded.
      const nlohmann::json& l = lights->json()[i];
      if (l.is_object() && l.contains("type") && l["type"] == "environment") {
        if (environment) {
          lights->element(i).fail("at most one environment light is allowed (another is at " +
                                  json_pointer_append(lights->path(), *environment) + ")");
        }
        environment = i;
      }
      scene.lights.push_back(parse_light(lights->element(i), ctx));
      // Layers name these two groups with their own meaning.
      const std::string& group = scene.lights.back().group;
      if (group == kDefaultLightGroup) {
        lights->element(i).fail_key(
            "group",
            "expected a group name other than \"default\" (the group of the lights "
            "without a 'group': leave the key out), got \"default\"");
      }
      if (group == kEmissionLightGroup) {
        lights->element(i).fail_key(
            "group",
            "expected a group name other than \"emission\" (reserved for emission from "
            "media), got \"emission\"");
      }
    }
  }

  // nlohmann's objects are sorted by key, so media come in name order (like
  // materials); the order does not matter since overlapping media add.
  if (const auto media = root.optional_child("media")) {
    media->expect_object();
    for (const auto& [name, value] : media->json().items()) {
      scene.media.push_back(
          parse_medium(JsonReader(value, ctx.file, media->key_path(name)), name, ctx));
    }
  }

  // After lights and media: layers name light groups and media.
  if (const auto layers = root.optional_child("layers")) {
    scene.layers = parse_layers(*layers, scene.lights, scene.media);
  }

  // Canonical text (sorted keys, no whitespace) so that reformatting a scene
  // does not change its hash, then the bytes of every referenced file.
  Fnv1a64 hash;
  hash.add_sized(doc.dump());
  for (const std::filesystem::path& p : ctx.referenced_files) {
    bool read_ok = false;  // the loaders have just read these files successfully
    hash.add_sized(read_file(p, read_ok));
  }
  scene.content_hash = hash.hex();
  return scene;
}

}  // namespace vesper
