#pragma once
// The parsed, validated content of a `vesper-scene/1` file, in the file's own
// units and double precision. Nothing here is camera-relative or Embree-ready;
// scene/scene_builder turns it into the render-time Scene.
//
// Every field below has been validated by the loader: finite numbers, positive
// sizes, existing materials, readable files. Code that consumes a
// SceneDescription may rely on that.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "renderer/lights/light_selection.h"
#include "renderer/math/rgb.h"
#include "renderer/math/transform.h"
#include "renderer/math/vec.h"
#include "renderer/output/exr_encoding.h"
#include "renderer/volume/density_grid.h"

namespace vesper {

struct CameraDesc {
  Vec3d from{0, 0, 1}, to{0, 0, 0}, up{0, 1, 0};
  double fov_degrees = 40;    // across the shorter image axis
  double aperture = 0;        // lens diameter in scene units; 0 = pinhole
  double focus_distance = 1;  // distance along the view direction to the focal plane
};

enum class FilterType { Box, Gaussian };

struct FilmDesc {
  int width = 256, height = 256;
  FilterType filter = FilterType::Box;
  // The EXR's encoding (docs/scene-format.md, Film): half applies to colour channels.
  ExrPixelType pixel_type = ExrPixelType::Float;
  ExrCompression compression = ExrCompression::Zip;
};

// Standard AOVs (render.aovs). The seven light-transport AOVs from Emission on
// partition the beauty: emission seen directly + {diffuse, specular, volume}
// x {direct, indirect}, classified by the first scattering event after the
// camera and by whether the light arrives after one event (direct) or more.
enum class Aov {
  Albedo,
  Normal,
  Depth,
  Emission,
  DiffuseDirect,
  DiffuseIndirect,
  SpecularDirect,
  SpecularIndirect,
  VolumeDirect,
  VolumeIndirect,
  Variance,    // variance.R/G/B: the variance of the beauty's pixel mean
  Spp,         // spp: samples taken in the pixel
  Cryptomatte  // CryptoObject00.., CryptoMaterial..: id mattes (render/cryptomatte.h)
};

struct RenderDesc {
  int spp = 16;
  int max_depth = 8;  // scattering events after the camera vertex; 1 = direct light only
  uint64_t seed = 0;
  std::vector<Aov> aovs;  // requested AOVs (render.aovs), in request order, no duplicates
  // Adaptive sampling and budgets (docs/scene-format.md, "render"): with a
  // noise target a pixel stops sampling once its estimated relative error of
  // the mean is below it; spp is then the default max_spp.
  std::optional<double> noise_target;
  std::optional<int> min_spp, max_spp;
  std::optional<double> time_limit;  // seconds of wall clock, checked after each pass
  // render.clamp: the largest RGB component a camera sample's indirect light
  // may have (integrator/path_context.h). Biased; unset = off.
  std::optional<double> clamp;
  // render.photon_merging: photon merging for multiple scattering in media
  // (integrator/photon_merging.h). Biased (consistent); off by default.
  // render.photon_radius: its kernel radius in scene units; unset = from
  // the photon count (photon_radius).
  bool photon_merging = false;
  std::optional<double> photon_radius;
  // render.shutter: [open, close] in frames, offsets from the frame rendered
  // (open <= close). Unset: no motion blur.
  struct Shutter {
    double open = 0, close = 0;
  };
  std::optional<Shutter> shutter;
  // render.light_selection: how next-event estimation picks a light
  // (lights/light_sampler.h).
  LightSelection light_selection = LightSelection::Spatial;
};

struct DiffuseMaterialDesc {
  Rgb albedo{0.8f};
};
struct ConductorMaterialDesc {
  double roughness = 0;        // perceptual; GGX alpha = roughness^2
  Rgb eta{0.2f, 0.92f, 1.1f};  // defaults: gold-ish
  Rgb k{3.9f, 2.45f, 2.14f};
};
struct DielectricMaterialDesc {
  double ior = 1.5;
  double roughness = 0;
};
struct PrincipledMaterialDesc {
  Rgb base_color{0.8f};
  double metallic = 0;
  double roughness = 0.5;
};
using MaterialDesc = std::variant<DiffuseMaterialDesc, ConductorMaterialDesc,
                                  DielectricMaterialDesc, PrincipledMaterialDesc>;

struct QuadShapeDesc {
  Vec3d corner, edge1, edge2;
};
struct SphereShapeDesc {
  Vec3d center;
  double radius = 1;
};
// A triangle mesh, already loaded (from `file` or inline) and transformed to world space.
struct MeshShapeDesc {
  std::vector<Vec3d> positions;
  std::vector<std::array<uint32_t, 3>> triangles;  // every index < positions.size()
  std::string source;                              // file path or "inline", for messages
};
using ShapeGeometry = std::variant<QuadShapeDesc, SphereShapeDesc, MeshShapeDesc>;
struct ShapeDesc {
  ShapeGeometry geometry;  // at the frame
  uint32_t material = 0;   // index into SceneDescription::materials
  std::string name;        // unique in the scene; "" = the default (shape_name)
  // Motion blur: the geometry at SceneDescription::motion_times (same type;
  // a mesh keeps its triangles); empty = still over the shutter.
  std::vector<ShapeGeometry> steps = {};
};

struct QuadLightDesc {
  Vec3d corner, edge1, edge2;
  Rgb radiance;  // emitted toward normalize(cross(edge1, edge2)), one-sided
};
struct PointLightDesc {
  Vec3d position;
  Rgb intensity;      // W/sr
  double radius = 0;  // scene units; > 0: a sphere light
};
struct SpotLightDesc {
  Vec3d position, direction;  // direction normalized by the loader
  Rgb intensity;
  double cone_angle = 30, falloff_start = 25;  // half-angles, degrees; falloff_start <= cone_angle
  double radius = 0;                           // scene units; > 0: a sphere light
};
struct SunLightDesc {
  Vec3d direction;   // from the scene toward the sun, normalized by the loader
  Rgb irradiance;    // measured perpendicular to `direction`
  double angle = 0;  // angular diameter in degrees; 0 = delta directional light
};
// Lat-long image, row 0 at the top (+Y pole). Pixels linear RGB, finite, >= 0.
struct EnvironmentImage {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;  // width * height, row-major
};
struct EnvironmentLightDesc {
  Rgb radiance{1.f};                      // constant radiance when `image` is empty
  std::optional<EnvironmentImage> image;  // from `file`
  std::string file;                       // resolved path, for messages and the scene hash
  double scale = 1;
  double rotation = 0;  // degrees about +Y
};
struct LightDesc {
  std::variant<QuadLightDesc, PointLightDesc, SpotLightDesc, SunLightDesc, EnvironmentLightDesc>
      light;
  std::string group;  // empty = no group
};

struct BoxDesc {
  Vec3d min, max;  // min < max on every axis
};
// Homogeneous participating medium; without bounds it fills the whole scene.
struct HomogeneousMediumDesc {
  Rgb sigma_a, sigma_s;  // per scene unit
  double g = 0;          // Henyey-Greenstein asymmetry, (-1, 1)
  std::optional<BoxDesc> bounds;
  // Motion blur: the bounds at SceneDescription::motion_times; empty = still.
  std::vector<BoxDesc> bounds_steps = {};
};
// Heterogeneous medium from an OpenVDB grid: sigma(x) = density(x) * density_scale * sigma.
// World position of index point p: transform.apply_point(density->index_to_world().apply_point(p)).
struct VdbMediumDesc {
  std::string file;  // resolved path, for messages and the hash
  std::string grid = "density";
  std::shared_ptr<const DensityGrid> density;  // loaded and validated
  double density_scale = 1;
  Rgb sigma_a, sigma_s{1.f};
  double g = 0;
  Transform transform;
  // Motion blur: the transform at SceneDescription::motion_times; empty = still.
  std::vector<Transform> transform_steps = {};
  std::string emission_grid;                    // empty = no emission
  std::shared_ptr<const DensityGrid> emission;  // loaded when emission_grid is set
  double emission_scale = 0;
  // Emission coefficient (radiance added per scene unit of path, as in Cycles):
  // emission(x) * emission_scale * emission_color, attenuated like any light.
  Rgb emission_color{1.f};
};
struct MediumDesc {
  std::string name;
  std::variant<HomogeneousMediumDesc, VdbMediumDesc> medium;
};

// Which light paths a layer keeps.
enum class PathSelection { All, Surface, Volume };

// Overrides for a variant layer's own render.
struct MediumOverride {
  std::optional<double> density_scale;  // homogeneous media: multiplies sigma_a and sigma_s
  std::optional<Rgb> sigma_a, sigma_s;
  std::optional<double> g;
  std::optional<bool> enabled;  // false removes the medium from this variant
};
struct VariantDesc {
  std::map<std::string, MediumOverride> media;     // keys name existing media
  std::optional<std::vector<std::string>> lights;  // active light groups; unset = all lights
};

// A named layer (`layers` in the scene file): a selection of the beauty's
// light paths, computed in the beauty's pass, or, with a variant, a separate
// render of the modified scene. Light groups are lights[].group; lights
// without a group are in group "default"; emission from media is group
// "emission".
struct LayerDesc {
  std::string name;  // a valid EXR layer name: [A-Za-z0-9_-]+, not an AOV name
  PathSelection paths = PathSelection::All;
  std::optional<std::vector<std::string>> lights;  // groups kept; unset = all
  std::optional<VariantDesc> variant;
};

struct SceneDescription {
  std::filesystem::path file;  // the scene file, for messages
  CameraDesc camera;           // at the frame (the render space is centred on it)
  // Motion blur (render.shutter, scene/motion_parse.cpp): the K >= 2 times,
  // in frames, spread uniformly over [frame + open, frame + close] that
  // moving cameras and shapes are sampled at; empty when nothing moves.
  std::vector<double> motion_times;
  std::vector<CameraDesc> camera_steps;  // at motion_times; empty = still camera
  FilmDesc film;
  RenderDesc render;
  std::vector<std::string> material_names;  // parallel to materials
  std::vector<MaterialDesc> materials;
  std::vector<ShapeDesc> shapes;
  std::vector<LightDesc> lights;  // at most one environment light
  std::vector<MediumDesc> media;  // sorted by name; overlapping media add their coefficients
  std::vector<LayerDesc> layers;  // sorted by name
  // FNV-1a 64 (16 hex digits) of the canonical JSON text + bytes of referenced files.
  std::string content_hash;
};

// A shape's name (Cryptomatte's object name): its "name", or its type and
// index in "shapes" ("quad3", "sphere0", "mesh7").
inline std::string shape_name(const SceneDescription& d, size_t index) {
  const ShapeDesc& s = d.shapes[index];
  if (!s.name.empty()) return s.name;
  static constexpr const char* kTypes[] = {"quad", "sphere", "mesh"};
  return kTypes[s.geometry.index()] + std::to_string(index);
}

}  // namespace vesper
