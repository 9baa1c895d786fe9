#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/scene/light_builder.h"
#include "renderer/scene/render_space.h"
#include "renderer/scene/scene.h"

namespace vesper {
namespace {

float alpha_from_roughness(double r) { return float(r * r); }

Bsdf make_bsdf(const MaterialDesc& m) {
  return std::visit(
      [](const auto& d) -> Bsdf {
        using T = std::decay_t<decltype(d)>;
        if constexpr (std::is_same_v<T, DiffuseMaterialDesc>)
          return DiffuseBsdf{d.albedo};
        else if constexpr (std::is_same_v<T, ConductorMaterialDesc>)
          return ConductorBsdf{alpha_from_roughness(d.roughness), d.eta, d.k};
        else if constexpr (std::is_same_v<T, DielectricMaterialDesc>)
          return DielectricBsdf{float(d.ior), alpha_from_roughness(d.roughness)};
        else
          return PrincipledBsdf{d.base_color, float(d.metallic), alpha_from_roughness(d.roughness)};
      },
      m);
}

Camera make_camera(const CameraDesc& cd, const FilmDesc& film, const RenderSpace& space) {
  Camera cam;
  cam.position = Vec3(0.f);
  const Vec3d fwd = normalize(cd.to - cd.from);
  const Vec3d right = normalize(cross(fwd, cd.up));
  cam.forward = Vec3(fwd);
  cam.right = Vec3(right);
  cam.up = Vec3(cross(right, fwd));
  cam.width = film.width;
  cam.height = film.height;
  const float t = float(std::tan(cd.fov_degrees * 0.5 * M_PI / 180.0));
  const float aspect = float(film.width) / float(film.height);
  if (aspect >= 1.f) {
    cam.tan_half_y = t;
    cam.tan_half_x = t * aspect;
  } else {
    cam.tan_half_x = t;
    cam.tan_half_y = t / aspect;
  }
  cam.lens_radius = float(0.5 * cd.aperture * space.inv_scale);
  cam.focus_distance = float(cd.focus_distance * space.inv_scale);
  return cam;
}

// A moving camera's steps; each sits where it is in render space (centred on
// the frame's camera).
std::vector<Camera> make_camera_steps(const SceneDescription& desc, const RenderSpace& space) {
  std::vector<Camera> steps;
  for (const CameraDesc& cd : desc.camera_steps) {
    steps.push_back(make_camera(cd, desc.film, space));
    steps.back().position = space.point(cd.from);
  }
  return steps;
}

// Everything the accelerator holds, in render space.
struct SceneSurfaces {
  std::vector<AccelQuad> quads;
  std::vector<AccelSphere> spheres;
  std::vector<AccelMesh> meshes;
};

// Render-space positions; one spare element so that Embree's 16-byte
// vertex loads stay inside the (shared) buffer.
std::vector<Vec3> render_positions(const std::vector<Vec3d>& world, const RenderSpace& space) {
  std::vector<Vec3> out;
  out.reserve(world.size() + 1);
  for (const auto& p : world) out.push_back(space.point(p));
  return out;
}

// Motion blur: the steps of a shape of type T, in render space, into `out`'s steps.
template <typename T>
void add_steps(const std::vector<ShapeGeometry>& steps, const RenderSpace& space, AccelQuad& out) {
  for (const ShapeGeometry& g : steps) {
    const auto& q = std::get<T>(g);
    out.steps.push_back({space.point(q.corner), space.vector(q.edge1), space.vector(q.edge2)});
  }
}
template <typename T>
void add_steps(const std::vector<ShapeGeometry>& steps, const RenderSpace& space,
               AccelSphere& out) {
  for (const ShapeGeometry& g : steps) {
    const auto& s = std::get<T>(g);
    out.steps.push_back({space.point(s.center), float(s.radius * space.inv_scale)});
  }
}
template <typename T>
void add_steps(const std::vector<ShapeGeometry>& steps, const RenderSpace& space, AccelMesh& out) {
  for (const ShapeGeometry& g : steps)
    out.steps.push_back(render_positions(std::get<T>(g).positions, space));
}

void add_shapes(const SceneDescription& desc, const RenderSpace& space, SceneSurfaces& geometry) {
  for (size_t i = 0; i < desc.shapes.size(); ++i) {
    const ShapeDesc& s = desc.shapes[i];
    const int32_t shape = int32_t(i);
    std::visit(
        [&](const auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, QuadShapeDesc>) {
            geometry.quads.push_back({space.point(g.corner),
                                      space.vector(g.edge1),
                                      space.vector(g.edge2),
                                      s.material,
                                      -1,
                                      shape,
                                      {}});
            add_steps<T>(s.steps, space, geometry.quads.back());
          } else if constexpr (std::is_same_v<T, SphereShapeDesc>) {
            geometry.spheres.push_back(
                {space.point(g.center), float(g.radius * space.inv_scale), s.material, shape, {}});
            add_steps<T>(s.steps, space, geometry.spheres.back());
          } else {
            AccelMesh m;
            m.positions = render_positions(g.positions, space);
            m.triangles = g.triangles;
            m.material = s.material;
            m.shape = shape;
            add_steps<T>(s.steps, space, m);
            geometry.meshes.push_back(std::move(m));
          }
        },
        s.geometry);
  }
}

// Lights in render space; emitters that are surfaces join the geometry.
void add_lights(const SceneDescription& desc, const RenderSpace& space, Scene& scene,
                SceneSurfaces& geometry) {
  for (const auto& ld : desc.lights) {
    const uint32_t index = uint32_t(scene.lights.size());
    RenderLight rl = make_render_light(ld, space);
    scene.lights.push_back(std::move(rl.light));
    if (rl.surface) {
      rl.surface->light = int32_t(index);
      geometry.quads.push_back(*rl.surface);
    }
    if (rl.at_infinity) scene.infinite_lights.push_back(index);
    if (scene.lights.back().is_sun()) scene.suns.push_back(index);
    scene.light_groups.push_back(ld.group);
  }
}

// Light groups for layers: the scene's groups in order of appearance, then
// "default" for lights without one, then "emission" (media) last.
void assign_light_groups(Scene& scene) {
  bool any_ungrouped = false;
  for (const auto& g : scene.light_groups) {
    if (g.empty())
      any_ungrouped = true;
    else if (std::find(scene.group_names.begin(), scene.group_names.end(), g) ==
             scene.group_names.end())
      scene.group_names.push_back(g);
  }
  if (any_ungrouped) scene.group_names.push_back("default");
  scene.group_names.push_back("emission");
  scene.emission_group = int(scene.group_names.size()) - 1;
  for (const auto& g : scene.light_groups) {
    const std::string name = g.empty() ? "default" : g;
    scene.light_group.push_back(
        int(std::find(scene.group_names.begin(), scene.group_names.end(), name) -
            scene.group_names.begin()));
  }
}

}  // namespace

Scene build_scene(const SceneDescription& desc, const SceneBuildOptions& options) {
  Scene scene;
  scene.film = desc.film;
  scene.render = desc.render;
  scene.content_hash = desc.content_hash;
  const RenderSpace space = make_render_space(desc);
  scene.origin = space.origin;
  scene.unit_scale = space.unit_scale;
  scene.radius = space.radius;
  scene.camera = make_camera(desc.camera, desc.film, space);
  for (const auto& m : desc.materials) scene.materials.push_back(make_bsdf(m));
  scene.material_names = desc.material_names;
  for (size_t i = 0; i < desc.shapes.size(); ++i) {
    scene.shape_names.push_back(shape_name(desc, i));
    scene.shape_materials.push_back(desc.shapes[i].material);
  }

  SceneSurfaces geometry;
  add_shapes(desc, space, geometry);
  add_lights(desc, space, scene, geometry);
  assign_light_groups(scene);
  scene.light_sampler = LightSampler(scene.lights, scene.radius, desc.render.light_selection);
  scene.media = build_media(desc, scene.origin, scene.unit_scale, options.media);
  scene.accel = std::make_unique<Accel>(std::move(geometry.quads), std::move(geometry.spheres),
                                        std::move(geometry.meshes));
  scene.camera_steps = make_camera_steps(desc, space);
  scene.motion_steps = desc.motion_times.size();
  // Something moves over the shutter: the camera, a shape or a medium.
  scene.motion_blur = !desc.motion_times.empty();
  return scene;
}

}  // namespace vesper
