// Parses one entry of "lights": quad, point, spot, sun or environment.
#include "renderer/scene/environment_image.h"
#include "renderer/scene/scene_parse.h"

namespace vesper {
namespace {

constexpr std::string_view kLightTypes[] = {"quad", "point", "spot", "sun", "environment"};

// Normalizes a direction; rescaling first keeps huge or tiny (but non-zero)
// inputs from overflowing or underflowing in the dot product.
Vec3d unit_direction(JsonReader& node, std::string_view key) {
  const Vec3d d = read_vec3(node, key);
  const double m = max_abs_component(d);
  if (!(m > 0)) node.fail_key(key, "expected a non-zero direction, got [0, 0, 0]");
  return normalize(d / m);
}

SpotLightDesc parse_spot(JsonReader& node) {
  SpotLightDesc spot;
  spot.position = read_vec3(node, "position");
  spot.direction = unit_direction(node, "direction");
  spot.intensity = read_rgb(node, "intensity", Range::non_negative());
  spot.cone_angle = node.number("cone_angle", Range::left_open(0, 180));
  spot.falloff_start = node.number("falloff_start", spot.cone_angle, Range::non_negative());
  spot.radius = node.number("radius", 0.0, Range::non_negative());
  if (spot.falloff_start > spot.cone_angle) {
    node.fail_key("falloff_start", "expected falloff_start <= cone_angle (" +
                                       describe_json(node.json()["cone_angle"]) + "), got " +
                                       describe_json(node.json()["falloff_start"]));
  }
  return spot;
}

EnvironmentLightDesc parse_environment(JsonReader& node, SceneParseContext& ctx) {
  EnvironmentLightDesc env;
  const auto radiance = node.optional_child("radiance");
  const auto file = node.optional_child("file");
  if (radiance && file) node.fail("use either 'radiance' or 'file', not both");
  if (!radiance && !file) node.fail("expected either 'radiance' or 'file'");
  if (radiance) {
    // `scale` and `rotation` only mean something for an image.
    for (std::string_view key : {"scale", "rotation"}) {
      if (node.has(key)) node.fail_key(key, "'" + std::string(key) + "' only applies with 'file'");
    }
    env.radiance = as_rgb(*radiance, Range::non_negative());
    return env;
  }
  const std::filesystem::path path = ctx.resolve(*file);
  env.image = load_environment_image(path, ctx.file, file->path());
  env.file = path.string();
  ctx.referenced_files.push_back(path);
  env.scale = node.number("scale", 1.0, Range::non_negative());
  env.rotation = node.number("rotation", 0.0);
  return env;
}

}  // namespace

LightDesc parse_light(JsonReader node, SceneParseContext& ctx) {
  node.expect_object();
  LightDesc light;
  switch (node.enumeration("type", kLightTypes)) {
    case 0: {
      node.allow_keys({"type", "corner", "edge1", "edge2", "radiance", "group"});
      // Zero-area quad lights are accepted: they emit nothing.
      light.light = QuadLightDesc{read_vec3(node, "corner"), read_vec3(node, "edge1"),
                                  read_vec3(node, "edge2"),
                                  read_rgb(node, "radiance", Range::non_negative())};
      break;
    }
    case 1: {
      node.allow_keys({"type", "position", "intensity", "radius", "group"});
      light.light = PointLightDesc{read_vec3(node, "position"),
                                   read_rgb(node, "intensity", Range::non_negative()),
                                   node.number("radius", 0.0, Range::non_negative())};
      break;
    }
    case 2: {
      node.allow_keys({"type", "position", "direction", "intensity", "cone_angle", "falloff_start",
                       "radius", "group"});
      light.light = parse_spot(node);
      break;
    }
    case 3: {
      node.allow_keys({"type", "direction", "irradiance", "angle", "group"});
      SunLightDesc sun;
      sun.direction = unit_direction(node, "direction");
      sun.irradiance = read_rgb(node, "irradiance", Range::non_negative());
      sun.angle = node.number("angle", 0.53, Range::right_open(0, 90));
      light.light = sun;
      break;
    }
    default: {
      node.allow_keys({"type", "radiance", "file", "scale", "rotation", "group"});
      light.light = parse_environment(node, ctx);
      break;
    }
  }
  if (const auto group = node.optional_child("group")) light.group = group->as_string();
  node.finish();
  return light;
}

}  // namespace vesper
