#pragma once
// Internal to the scene loader: the pieces of parse_scene that live in their
// own files (shapes, lights, media, transforms, layers). Not a public header.
#include <filesystem>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "renderer/scene/aov_names.h"
#include "renderer/scene/json_values.h"
#include "renderer/scene/scene_description.h"

namespace vesper {

// Light groups with a fixed meaning: the lights without a `group`, and
// emission from media. Neither may be written as a light's `group`.
inline constexpr std::string_view kDefaultLightGroup = "default";
inline constexpr std::string_view kEmissionLightGroup = "emission";

struct SceneParseContext {
  std::string file;                // the scene file, for messages
  std::filesystem::path base_dir;  // relative paths resolve against this
  bool scene_dir_only = false;     // SceneLoadOptions::scene_dir_only
  long frame = 1;                  // fills the '#' run of per-frame files (common/frame_pattern.h)
  std::vector<std::string> material_names;
  std::vector<std::filesystem::path>
      referenced_files;  // meshes, images and .vdb files, for the hash

  // The file named by the string `node` (a "file" key): relative to base_dir,
  // absolute as it is — unless scene_dir_only, which refuses (at `node`) a
  // path that could leave base_dir (common/scene_reference.h). A '#' run in
  // the file name is `frame`; a missing frame of a sequence is refused at `node`.
  std::filesystem::path resolve(const JsonReader& node) const;
  // Index of the material named by `key`; the error lists the known names.
  uint32_t material(JsonReader& node, std::string_view key) const;
};

// `T` of docs/scene-format.md: translate/rotate/scale or a row-major matrix.
// Refuses a transform whose matrix or inverse is not finite.
Transform parse_transform(JsonReader node);
// Whether every entry of t's matrix and of its inverse is at most `limit` in
// magnitude (and not NaN).
bool transform_fits(const Transform& t, double limit);

CameraDesc parse_camera(JsonReader node);
ShapeDesc parse_shape(JsonReader node, SceneParseContext& ctx);
// Gives every shape its name (the default where it has none: shape_name) and
// refuses a name two shapes share, at the second one's JSON path.
void name_shapes(const JsonReader& shapes, SceneDescription& scene);
// Refuses (at `node`) an extent beyond kMaxWorldCoordinate (render_space.h).
void check_extent(const JsonReader& node, double extent);
// Motion blur (scene/motion_parse.cpp): with scene.render.shutter, the camera
// and the shapes that hold keyframes in `keyed` (the scene document before
// evaluation) sampled over [frame + open, frame + close] into
// scene.motion_times, camera_steps and each shape's steps; the content hash
// then covers them too.
void parse_motion(const nlohmann::json& keyed, double frame, SceneParseContext& ctx,
                  SceneDescription& scene);
LightDesc parse_light(JsonReader node, SceneParseContext& ctx);
// A box {"min", "max"}, min < max on every axis.
BoxDesc parse_box(JsonReader node);
// Refuses (at `node`'s "transform", or "file") a grid transform that maps
// beyond the float range rendering uses.
void check_grid_transform(JsonReader& node, const Transform& transform, const DensityGrid& grid);
// One entry of "media" (`name` is its key); loads and validates .vdb grids.
MediumDesc parse_medium(JsonReader node, const std::string& name, SceneParseContext& ctx);
// The "layers" object, sorted by name; light groups and variant media are
// checked against the already parsed `lights` and `media`.
std::vector<LayerDesc> parse_layers(JsonReader node, const std::vector<LightDesc>& lights,
                                    const std::vector<MediumDesc>& media);

}  // namespace vesper
