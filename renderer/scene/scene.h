#pragma once
// The render-time scene: camera-relative, rescaled to unit size, with Embree
// geometry, BSDFs and lights ready for the integrator.
//
// Render space = (world - camera position) / unit_scale. Keeping the camera at
// the origin and the scene near unit size keeps float precision and ray
// offsets independent of where the scene sits and how large it is.
#include <memory>
#include <string>
#include <vector>

#include "renderer/bsdf/bsdf.h"
#include "renderer/core/accel.h"
#include "renderer/core/camera.h"
#include "renderer/lights/light_sampler.h"
#include "renderer/media/media_set.h"
#include "renderer/scene/media_builder.h"
#include "renderer/scene/scene_description.h"

namespace vesper {

struct Scene {
  Camera camera;
  // Motion blur (render.shutter with something moving): each camera sample
  // draws a time in the shutter (Sampler::shutter_time), its path lives at
  // that instant. False: no time is drawn and the BVH is static.
  bool motion_blur = false;
  size_t motion_steps = 0;           // SceneDescription::motion_times.size()
  std::vector<Camera> camera_steps;  // a moving camera's K >= 2 steps; empty = `camera`
  FilmDesc film;
  RenderDesc render;
  std::vector<Bsdf> materials;
  // Cryptomatte's names: every shape's (shape_name) and material, and each shape's material.
  std::vector<std::string> shape_names, material_names;
  std::vector<uint32_t> shape_materials;
  std::vector<Light> lights;
  std::vector<std::string> light_groups;  // parallel to lights; "" = no group
  // Light groups for layers: every distinct `group`, then "default" (lights
  // without a group) if any, then "emission" (media emission), always last.
  std::vector<std::string> group_names;
  std::vector<int> light_group;  // parallel to lights: index into group_names
  int emission_group = 0;
  std::vector<uint32_t> infinite_lights;  // lights a ray that escapes can hit
  std::vector<uint32_t> suns;             // sun lights, with or without an angle (sun_shaft.h)
  LightSampler light_sampler;
  std::unique_ptr<Accel> accel;
  MediaSet media;         // empty: no medium code runs at all
  Vec3d origin;           // world position of render-space (0,0,0)
  double unit_scale = 1;  // world units per render-space unit
  float radius = 1;       // bounding radius of the render-space scene around the origin
  std::string content_hash;
};

struct SceneBuildOptions {
  MediaBuildOptions media;
};

Scene build_scene(const SceneDescription& desc, const SceneBuildOptions& options = {});

}  // namespace vesper
