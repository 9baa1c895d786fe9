// Motion blur (docs/scene-format.md, "Motion blur"): the camera and the shapes
// that move are sampled at K times spread uniformly over the shutter
// [frame + open, frame + close]; lights, materials and media stay at the
// frame itself. K = 2 (the renderer interpolates linearly between steps, as
// Embree does) when every key involved is linear, none lies strictly inside
// the shutter and none is under a rotation; otherwise kMaxMotionSteps.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/keyframes.h"
#include "renderer/scene/render_space.h"
#include "renderer/scene/scene_parse.h"

namespace vesper {
namespace {

// The cap on motion steps: 8 linear segments over the shutter follow a smooth
// curve or a rotation closely enough for a blur, and keep the BVH small.
constexpr int kMaxMotionSteps = 9;

// Whether linear interpolation between the shutter's ends would miss the
// motion of the keyframe objects inside `node`: a smooth curve, a key strictly
// inside (t0, t1), or keys under a rotation (not linear in positions).
bool needs_more_steps(const nlohmann::json& node, double t0, double t1, bool in_rotation) {
  if (is_keyframed(node)) {
    if (in_rotation || node.value("interp", std::string("linear")) != "linear") return true;
    for (const auto& key : node["keys"]) {
      const double t = key.at(0).get<double>();
      if (t > t0 && t < t1) return true;
    }
    return false;
  }
  if (node.is_object()) {
    for (const auto& [name, value] : node.items())
      if (needs_more_steps(value, t0, t1, in_rotation || name == "rotate" || name == "matrix"))
        return true;
  } else if (node.is_array()) {
    for (const auto& value : node)
      if (needs_more_steps(value, t0, t1, in_rotation)) return true;
  }
  return false;
}

// The keyed parts of the document that move: the camera, the shapes with
// keyframes (other shapes as null, so JSON paths keep their indices), and
// the media whose placement is keyed (a box's bounds, a VDB's transform).
struct MovingParts {
  nlohmann::json doc = nlohmann::json::object();
  bool camera = false;
  std::vector<size_t> shapes;
  std::vector<std::string> media;  // names; each holds only its keyed placement
  bool empty() const { return !camera && shapes.empty() && media.empty(); }
};

void add_moving_media(const nlohmann::json& keyed, MovingParts& parts) {
  const auto media = keyed.find("media");
  if (media == keyed.end() || !media->is_object()) return;
  for (const auto& [name, m] : media->items()) {
    if (!m.is_object()) continue;
    for (const char* key : {"bounds", "transform"}) {
      if (const auto v = m.find(key); v != m.end() && has_keyframes(*v)) {
        parts.doc["media"][name] = {{key, *v}};
        parts.media.push_back(name);
      }
    }
  }
}

MovingParts moving_parts(const nlohmann::json& keyed) {
  MovingParts parts;
  if (const auto c = keyed.find("camera"); c != keyed.end() && has_keyframes(*c)) {
    parts.camera = true;
    parts.doc["camera"] = *c;
  }
  const auto shapes = keyed.find("shapes");
  if (shapes == keyed.end() || !shapes->is_array()) return parts;
  parts.doc["shapes"] = nlohmann::json::array();
  for (size_t i = 0; i < shapes->size(); ++i) {
    const bool keyed_shape = has_keyframes((*shapes)[i]);
    parts.doc["shapes"].push_back(keyed_shape ? (*shapes)[i] : nlohmann::json());
    if (keyed_shape) parts.shapes.push_back(i);
  }
  return parts;
}

MediumDesc& medium_named(SceneDescription& scene, const std::string& name) {
  for (MediumDesc& m : scene.media)
    if (m.name == name) return m;
  throw std::logic_error("no medium " + name);  // parsed from the same document
}

// A moving medium's placement at one step: a homogeneous box's bounds (only
// a bounded box can move) or a VDB's transform.
void parse_medium_step(JsonReader media, const std::string& name, MediumDesc& medium) {
  JsonReader node = media.object(name);
  if (auto* h = std::get_if<HomogeneousMediumDesc>(&medium.medium)) {
    const BoxDesc box = parse_box(node.object("bounds"));
    check_extent(node, std::max({max_abs_component(box.min), max_abs_component(box.max)}));
    h->bounds_steps.push_back(box);
    return;
  }
  auto& v = std::get<VdbMediumDesc>(medium.medium);
  const Transform t = parse_transform(node.child("transform"));
  check_grid_transform(node, t, *v.density);
  if (v.emission) check_grid_transform(node, t, *v.emission);
  v.transform_steps.push_back(t);
}

// A step must be the same shape as at the frame: same type, a mesh with the
// same vertices and triangles (only positions move).
void check_same_shape(const JsonReader& node, const ShapeGeometry& frame,
                      const ShapeGeometry& step) {
  if (frame.index() != step.index()) node.fail("expected the same shape type at every time");
  const auto* a = std::get_if<MeshShapeDesc>(&frame);
  const auto* b = std::get_if<MeshShapeDesc>(&step);
  if (a && (a->positions.size() != b->positions.size() || a->triangles != b->triangles))
    node.fail(
        "expected the same mesh (vertex count and triangles) at every time in the shutter; only "
        "its positions may move");
}

// The camera and moving shapes of the step document at one time.
void parse_step(const nlohmann::json& step_doc, const MovingParts& parts, SceneParseContext& ctx,
                SceneDescription& scene, std::vector<ShapeDesc>& shapes) {
  JsonReader root(step_doc, ctx.file, "");
  if (parts.camera) scene.camera_steps.push_back(parse_camera(root.object("camera")));
  for (size_t k = 0; k < parts.shapes.size(); ++k) {
    const size_t i = parts.shapes[k];
    const JsonReader node = root.array("shapes").element(i);
    ShapeDesc s = parse_shape(node, ctx);
    check_extent(node, extent_of(s));
    check_same_shape(node, scene.shapes[i].geometry, s.geometry);
    shapes[k] = std::move(s);
  }
  for (const std::string& name : parts.media)
    parse_medium_step(root.object("media"), name, medium_named(scene, name));
}

// The parts whose keyed values hold over the shutter (every step alike, as
// with a zero-length shutter, or keys that end before it): they do not move.
MovingParts held_parts(const std::vector<nlohmann::json>& step_docs, const MovingParts& parts) {
  auto held = [&](const nlohmann::json::json_pointer& at) {
    for (const nlohmann::json& d : step_docs)
      if (d.at(at) != step_docs.front().at(at)) return false;
    return true;
  };
  using Ptr = nlohmann::json::json_pointer;
  MovingParts out;
  out.camera = parts.camera && held(Ptr("/camera"));
  for (size_t i : parts.shapes)
    if (held(Ptr("/shapes/" + std::to_string(i)))) out.shapes.push_back(i);
  for (const std::string& name : parts.media)
    if (held(Ptr("/media") / name)) out.media.push_back(name);
  return out;
}

// Parts that do not move take their one value (that of every step).
void take_instant(const MovingParts& parts, SceneDescription& scene) {
  if (parts.camera) {
    scene.camera = scene.camera_steps.front();
    scene.camera_steps.clear();
  }
  for (size_t i : parts.shapes) {
    scene.shapes[i].geometry = std::move(scene.shapes[i].steps.front());
    scene.shapes[i].steps.clear();
  }
  for (const std::string& name : parts.media) {
    MediumDesc& m = medium_named(scene, name);
    if (auto* h = std::get_if<HomogeneousMediumDesc>(&m.medium)) {
      h->bounds = h->bounds_steps.front();
      h->bounds_steps.clear();
    } else {
      auto& v = std::get<VdbMediumDesc>(m.medium);
      v.transform = v.transform_steps.front();
      v.transform_steps.clear();
    }
  }
}

std::vector<double> shutter_times(double t0, double t1, int steps) {
  std::vector<double> times(size_t(steps), t0);
  for (int k = 1; k < steps; ++k) times[size_t(k)] = t0 + (t1 - t0) * double(k) / double(steps - 1);
  return times;
}

}  // namespace

void parse_motion(const nlohmann::json& keyed, double frame, SceneParseContext& ctx,
                  SceneDescription& scene) {
  MovingParts parts = moving_parts(keyed);
  add_moving_media(keyed, parts);
  if (parts.empty()) return;
  const double t0 = frame + scene.render.shutter->open, t1 = frame + scene.render.shutter->close;
  // A zero-length shutter is an instant: the frame's camera, shapes and
  // media placements are those of frame + open, without motion blur.
  const int steps = t0 == t1 ? 1 : needs_more_steps(parts.doc, t0, t1, false) ? kMaxMotionSteps : 2;
  const std::vector<double> times = shutter_times(t0, t1, steps);
  // Step shapes reload their mesh files: the hash counts each file once.
  const std::vector<std::filesystem::path> files = ctx.referenced_files;
  std::vector<nlohmann::json> step_docs;
  std::vector<std::vector<ShapeDesc>> shapes(times.size(),
                                             std::vector<ShapeDesc>(parts.shapes.size()));
  for (size_t k = 0; k < times.size(); ++k) {
    const nlohmann::json step_doc = evaluate_keyframes(parts.doc, times[k], ctx.file);
    parse_step(step_doc, parts, ctx, scene, shapes[k]);
    step_docs.push_back(step_doc);
  }
  ctx.referenced_files = files;
  for (size_t j = 0; j < parts.shapes.size(); ++j) {
    ShapeDesc& shape = scene.shapes[parts.shapes[j]];
    for (auto& step : shapes) shape.steps.push_back(std::move(step[j].geometry));
  }
  const MovingParts held = held_parts(step_docs, parts);
  take_instant(held, scene);
  const bool all_held = held.camera == parts.camera && held.shapes.size() == parts.shapes.size() &&
                        held.media.size() == parts.media.size();
  if (!all_held) scene.motion_times = times;
}

}  // namespace vesper
