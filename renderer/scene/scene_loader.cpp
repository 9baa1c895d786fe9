// load_scene / parse_scene: the top level of `vesper-scene/1` plus camera,
// film, render and materials. Shapes, lights, media, layers and transforms have their own files.
#include "renderer/scene/scene_loader.h"

#include <climits>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "common/frame_pattern.h"
#include "common/json_parse.h"
#include "common/keyframes.h"
#include "common/scene_hash.h"
#include "common/scene_reference.h"
#include "renderer/output/metadata_text.h"
#include "renderer/scene/aov_list.h"
#include "renderer/scene/render_space.h"
#include "renderer/scene/scene_parse.h"

namespace vesper {
namespace {

constexpr std::string_view kFormat = "vesper-scene/1";
constexpr std::string_view kCameraTypes[] = {"perspective"};
constexpr std::string_view kFilters[] = {"box", "gaussian"};
constexpr std::string_view kMaterialTypes[] = {"diffuse", "conductor", "dielectric", "principled"};

}  // namespace

CameraDesc parse_camera(JsonReader node) {
  node.expect_object();
  node.enumeration("type", kCameraTypes);
  node.allow_keys({"type", "from", "to", "up", "fov", "aperture", "focus_distance"});
  CameraDesc cam;
  cam.from = read_vec3(node, "from");
  cam.to = read_vec3(node, "to");
  cam.up = read_vec3(node, "up");
  cam.fov_degrees = node.number("fov", Range::open(0, 180));
  // Lengths within the world limit (render_space.h): an aperture of 1.8e308
  // made the lens radius, and every ray, infinite.
  cam.aperture = node.number("aperture", 0.0, Range::closed(0, kMaxWorldCoordinate));
  const Vec3d forward = cam.to - cam.from;
  if (!(max_abs_component(forward) > 0)) {
    node.fail_key("to", "expected 'to' to differ from 'from'");
  }
  // The camera's frame is built from normalize(to - from): a distance beyond
  // the double range (from 1e308, to -1e308) made every camera ray NaN.
  if (!std::isfinite(length(forward))) {
    node.fail_key("to",
                  "expected 'to' at a distance from 'from' within the double range, got an "
                  "infinite distance");
  }
  const Vec3d f = normalize(forward / max_abs_component(forward));
  const double up_scale = max_abs_component(cam.up);
  if (!(up_scale > 0) || length(cross(f, normalize(cam.up / up_scale))) < 1e-6) {
    node.fail_key("up", "expected an up vector not parallel to the view direction (to - from)");
  }
  cam.focus_distance =
      node.number("focus_distance", length(forward), Range::left_open(0, kMaxWorldCoordinate));
  return cam;
}

namespace {

FilmDesc parse_film(JsonReader node) {
  node.expect_object();
  node.allow_keys({"width", "height", "filter", "pixel_type", "compression"});
  FilmDesc film;
  film.width = int(node.integer("width", 1, 65536));
  film.height = int(node.integer("height", 1, 65536));
  film.filter =
      node.enumeration("filter", 0, kFilters) == 0 ? FilterType::Box : FilterType::Gaussian;
  film.pixel_type = ExrPixelType(node.enumeration("pixel_type", 0, kExrPixelTypeNames));
  film.compression = ExrCompression(node.enumeration("compression", 0, kExrCompressionNames));
  return film;
}

// render.noise_target / min_spp / max_spp / time_limit.
void parse_sampling_budget(JsonReader& node, RenderDesc& render) {
  if (node.optional_child("noise_target"))
    render.noise_target = node.number("noise_target", Range::positive());
  if (node.optional_child("min_spp")) render.min_spp = int(node.integer("min_spp", 1, INT_MAX));
  if (node.optional_child("max_spp")) render.max_spp = int(node.integer("max_spp", 1, INT_MAX));
  if (render.min_spp && render.max_spp && *render.min_spp > *render.max_spp)
    node.fail_key("min_spp", "min_spp " + std::to_string(*render.min_spp) +
                                 " is greater than max_spp " + std::to_string(*render.max_spp));
  if (node.optional_child("time_limit"))
    render.time_limit = node.number("time_limit", Range::positive());
  if (node.optional_child("clamp")) render.clamp = node.number("clamp", Range::positive());
}

// render.shutter: [open, close], frames relative to the frame rendered.
void parse_shutter(JsonReader& node, RenderDesc& render) {
  const auto shutter = node.optional_child("shutter");
  if (!shutter) return;
  const std::vector<double> v = shutter->as_number_array();
  if (v.size() != 2)
    shutter->fail("expected [open, close] (2 numbers, frames relative to the frame), got " +
                  std::to_string(v.size()) + " numbers");
  if (!(v[0] <= v[1]))
    shutter->fail("expected open <= close, got open " + describe_json(v[0]) + " after close " +
                  describe_json(v[1]));
  render.shutter = RenderDesc::Shutter{v[0], v[1]};
}

RenderDesc parse_render(JsonReader node) {
  node.expect_object();
  node.allow_keys({"spp", "max_depth", "seed", "aovs", "noise_target", "min_spp", "max_spp",
                   "time_limit", "clamp", "shutter", "light_selection", "photon_merging",
                   "photon_radius"});
  RenderDesc render;
  render.spp = int(node.integer("spp", 1, INT_MAX));
  render.max_depth = int(node.integer("max_depth", 8, 1, INT_MAX));
  if (const auto seed = node.optional_child("seed")) render.seed = seed->as_uint64();
  if (const auto aovs = node.optional_child("aovs")) render.aovs = read_aov_list(*aovs);
  parse_sampling_budget(node, render);
  parse_shutter(node, render);
  render.photon_merging = node.boolean("photon_merging", false);
  if (node.optional_child("photon_radius"))
    render.photon_radius = node.number("photon_radius", Range::positive());
  static constexpr std::string_view kLightSelections[] = {"spatial", "power_uniform", "tree"};
  render.light_selection = LightSelection(node.enumeration("light_selection", 0, kLightSelections));
  return render;
}

MaterialDesc parse_material(JsonReader node) {
  node.expect_object();
  const Range unit = Range::closed(0, 1);
  switch (node.enumeration("type", kMaterialTypes)) {
    case 0: {
      node.allow_keys({"type", "albedo"});
      DiffuseMaterialDesc m;
      m.albedo = read_rgb(node, "albedo", m.albedo, unit);
      return m;
    }
    case 1: {
      node.allow_keys({"type", "roughness", "eta", "k"});
      ConductorMaterialDesc m;
      m.roughness = node.number("roughness", m.roughness, unit);
      m.eta = read_rgb(node, "eta", m.eta, Range::positive());
      m.k = read_rgb(node, "k", m.k, Range::non_negative());
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
      m.base_color = read_rgb(node, "base_color", m.base_color, unit);
      m.metallic = node.number("metallic", m.metallic, unit);
      m.roughness = node.number("roughness", m.roughness, unit);
      return m;
    }
  }
}

// name -> material, in name order (nlohmann's objects are sorted by key).
void parse_materials(JsonReader materials, SceneDescription& scene) {
  for (const auto& [name, value] : materials.json().items()) {
    JsonReader m(value, materials.file(), materials.key_path(name));
    if (name.empty()) m.fail("expected a non-empty material name");
    scene.materials.push_back(parse_material(m));
    scene.material_names.push_back(name);
  }
}

// Layers name these two groups with their own meaning.
void check_light_group(JsonReader light, const std::string& group) {
  if (group == kDefaultLightGroup) {
    light.fail_key("group",
                   "expected a group name other than \"default\" (the group of the lights "
                   "without a 'group': leave the key out), got \"default\"");
  }
  if (group == kEmissionLightGroup) {
    light.fail_key("group",
                   "expected a group name other than \"emission\" (reserved for emission from "
                   "media), got \"emission\"");
  }
}

}  // namespace

// Shapes, lights and bounded media stay within kMaxWorldCoordinate, after
// their transforms (render_space.h says why).
void check_extent(const JsonReader& node, double extent) {
  if (!(extent <= kMaxWorldCoordinate))
    node.fail(
        "expected it within 1e30 units of the origin on every axis (after its transform), "
        "got coordinates up to " +
        (std::isfinite(extent) ? describe_json(extent) : std::string("infinity")));
}

namespace {

void parse_lights(const JsonReader& lights, SceneParseContext& ctx, SceneDescription& scene) {
  lights.expect_array();
  std::optional<size_t> environment;
  for (size_t i = 0; i < lights.size(); ++i) {
    // Checked before parsing so a second environment image is not even loaded.
    const nlohmann::json& l = lights.json()[i];
    if (l.is_object() && l.contains("type") && l["type"] == "environment") {
      if (environment) {
        lights.element(i).fail("at most one environment light is allowed (another is at " +
                               json_pointer_append(lights.path(), *environment) + ")");
      }
      environment = i;
    }
    scene.lights.push_back(parse_light(lights.element(i), ctx));
    check_extent(lights.element(i), extent_of(scene.lights.back()));
    check_light_group(lights.element(i), scene.lights.back().group);
  }
}

// Canonical text (sorted keys, no whitespace) so that reformatting a scene
// does not change its hash, then the bytes of every referenced file, in the
// order common/scene_hash.h states (the farm server hashes the same way).
std::string content_hash(const nlohmann::json& doc, const SceneParseContext& ctx) {
  SceneHash hash(doc);
  for (const std::filesystem::path& p : ctx.referenced_files) {
    hash.add_file(read_text_file(p, "a file the scene references"));
  }
  return hash.hex();
}

SceneDescription parse_frame_document(const nlohmann::json& doc, const nlohmann::json* keyed,
                                      const std::filesystem::path& file,
                                      const SceneLoadOptions& options);

// The frame whose files a scene loaded at `time` reads: the nearest whole frame.
long file_frame(double time) { return std::lround(time); }

// Whether the value at `path` of `doc`, or a value containing it, is keyframed.
bool keyed_at(const nlohmann::json& doc, const std::string& path) {
  try {
    for (nlohmann::json::json_pointer p(path);; p = p.parent_pointer()) {
      if (doc.contains(p) && is_keyframed(doc.at(p))) return true;
      if (p.empty()) return false;
    }
  } catch (const nlohmann::json::exception&) {  // not a pointer into doc
    return false;
  }
}

// A scene over time is parsed as the document of one frame: every keyframed
// value evaluated at options.frame (and, under a shutter, the camera and
// shapes at times around it: motion_parse.cpp). A scene without keys is its
// own frame document, so its hash is what it always was. A value refused after
// evaluation says so, and at which frame, since the file holds no such value.
SceneDescription parse_document(const nlohmann::json& doc, const std::filesystem::path& file,
                                const SceneLoadOptions& options) {
  if (!has_keyframes(doc)) return parse_frame_document(doc, nullptr, file, options);
  const nlohmann::json frame_doc = evaluate_keyframes(doc, options.frame, file.string());
  try {
    return parse_frame_document(frame_doc, &doc, file, options);
  } catch (const JsonError& e) {
    if (!keyed_at(doc, e.json_path())) throw;
    throw SceneError(e.file(), e.json_path(),
                     e.message() + " (keyed; at frame " + metadata_number(options.frame) + ")");
  }
}

// `keyed`: the document with its keyframes, when it has any.
SceneDescription parse_frame_document(const nlohmann::json& doc, const nlohmann::json* keyed,
                                      const std::filesystem::path& file,
                                      const SceneLoadOptions& options) {
  SceneParseContext ctx;
  ctx.file = file.string();
  ctx.base_dir = file.parent_path();
  ctx.scene_dir_only = options.scene_dir_only;
  ctx.frame = file_frame(options.frame);
  JsonReader root(doc, ctx.file, "");
  root.expect_object();

  // The version decides what the rest means, so it is checked before anything else.
  root.child("format").expect_string(kFormat);
  root.allow_keys(
      {"format", "camera", "film", "render", "materials", "shapes", "lights", "media", "layers"});

  SceneDescription scene;
  scene.file = file;
  scene.camera = parse_camera(root.object("camera"));
  scene.film = parse_film(root.object("film"));
  scene.render = parse_render(root.object("render"));
  parse_materials(root.object("materials"), scene);
  ctx.material_names = scene.material_names;

  const JsonReader shapes = root.array("shapes");
  for (size_t i = 0; i < shapes.size(); ++i) {
    scene.shapes.push_back(parse_shape(shapes.element(i), ctx));
    check_extent(shapes.element(i), extent_of(scene.shapes.back()));
  }
  name_shapes(shapes, scene);
  if (const auto lights = root.optional_child("lights")) parse_lights(*lights, ctx, scene);

  // Media come in name order, like materials; the order does not matter since
  // overlapping media add.
  if (const auto media = root.optional_child("media")) {
    media->expect_object();
    for (const auto& [name, value] : media->json().items()) {
      const JsonReader medium(value, ctx.file, media->key_path(name));
      scene.media.push_back(parse_medium(medium, name, ctx));
      check_extent(medium, extent_of(scene.media.back()));
    }
  }
  // After lights and media: layers name light groups and media.
  if (const auto layers = root.optional_child("layers")) {
    scene.layers = parse_layers(*layers, scene.lights, scene.media);
  }
  scene.content_hash = content_hash(doc, ctx);
  if (keyed && scene.render.shutter) {
    parse_motion(*keyed, options.frame, ctx, scene);
    // The farm's result check and reuse extend the hash by the same rule.
    scene.content_hash =
        hash_with_shutter(scene.content_hash, shutter_state(*keyed, options.frame, ctx.file));
  }
  return scene;
}

// The reader and the JSON parser throw JsonError; callers of the scene loader
// catch SceneError (a scene's mesh and image loaders throw it directly).
template <typename Parse>
SceneDescription as_scene_error(Parse parse) {
  try {
    return parse();
  } catch (const SceneError&) {
    throw;
  } catch (const JsonError& e) {
    throw SceneError(e.file(), e.json_path(), e.message());
  }
}

}  // namespace

std::filesystem::path SceneParseContext::resolve(const JsonReader& node) const {
  const std::string ref = node.as_string();
  if (scene_dir_only)
    if (const std::string why = outside_reference_problem(ref); !why.empty())
      node.fail("'" + ref + "' " + why);
  const std::filesystem::path p(ref);
  const std::filesystem::path pattern = p.is_absolute() ? p : base_dir / p;
  if (!has_frame_pattern(pattern)) return pattern;
  const std::filesystem::path file = frame_path(pattern, frame);
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    node.fail("frame " + std::to_string(frame) + " of the sequence '" + ref +
              "': " + file.string() + " does not exist");
  return file;
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

SceneDescription load_scene(const std::filesystem::path& file, const SceneLoadOptions& options) {
  // A thin wrapper over the text entry point, so that both report the same errors.
  return as_scene_error(
      [&] { return parse_scene_text(read_text_file(file, "the scene file"), file, options); });
}

SceneDescription parse_scene_text(const std::string& text, const std::filesystem::path& file,
                                  const SceneLoadOptions& options) {
  return as_scene_error(
      [&] { return parse_document(parse_json(text, file.string()), file, options); });
}

SceneDescription parse_scene(const nlohmann::json& doc, const std::filesystem::path& file,
                             const SceneLoadOptions& options) {
  return as_scene_error([&] { return parse_document(doc, file, options); });
}

}  // namespace vesper
