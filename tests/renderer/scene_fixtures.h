#pragma once
// Small scenes built in code for tests (no JSON, so the tests do not depend on
// the loader).
#include "renderer/scene/scene_description.h"

namespace vesper::test {

inline SceneDescription empty_scene(int w, int h, int spp, int max_depth) {
  SceneDescription d;
  d.file = "test-scene";
  d.film.width = w;
  d.film.height = h;
  d.render.spp = spp;
  d.render.max_depth = max_depth;
  d.render.seed = 7;
  return d;
}

inline uint32_t add_material(SceneDescription& d, const std::string& name, MaterialDesc m) {
  d.material_names.push_back(name);
  d.materials.push_back(std::move(m));
  return uint32_t(d.materials.size() - 1);
}

inline void add_sphere(SceneDescription& d, Vec3d c, double r, uint32_t material) {
  d.shapes.push_back({SphereShapeDesc{c, r}, material, {}});
}
inline void add_quad(SceneDescription& d, Vec3d corner, Vec3d e1, Vec3d e2, uint32_t material) {
  d.shapes.push_back({QuadShapeDesc{corner, e1, e2}, material, {}});
}

template <typename L>
inline void add_light(SceneDescription& d, L light, std::string group = "") {
  LightDesc& l = d.lights.emplace_back();
  l.light = std::move(light);
  l.group = std::move(group);
}

// A homogeneous medium filling the box lo..hi.
inline HomogeneousMediumDesc fog_box(Rgb sa, Rgb ss, double g, Vec3d lo, Vec3d hi) {
  HomogeneousMediumDesc m;
  m.sigma_a = sa;
  m.sigma_s = ss;
  m.g = g;
  m.bounds = BoxDesc{lo, hi};
  return m;
}

inline void add_medium(SceneDescription& d, std::string name,
                       std::variant<HomogeneousMediumDesc, VdbMediumDesc> m) {
  MediumDesc& md = d.media.emplace_back();
  md.name = std::move(name);
  md.medium = std::move(m);
}

// A Cornell-style box: 2 units wide, quad ceiling light, a sphere and a box-ish quad.
inline SceneDescription small_cornell(int w, int h, int spp) {
  SceneDescription d = empty_scene(w, h, spp, 6);
  d.camera.from = {0, 1, 3.9};
  d.camera.to = {0, 1, 0};
  d.camera.fov_degrees = 37;
  const uint32_t white = add_material(d, "white", DiffuseMaterialDesc{Rgb(0.73f)});
  const uint32_t red = add_material(d, "red", DiffuseMaterialDesc{Rgb(0.63f, 0.065f, 0.05f)});
  const uint32_t green = add_material(d, "green", DiffuseMaterialDesc{Rgb(0.14f, 0.45f, 0.091f)});
  const uint32_t metal = add_material(d, "metal", ConductorMaterialDesc{0.3, Rgb(0.2f), Rgb(3.f)});
  add_quad(d, {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, white);
  add_quad(d, {-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, white);
  add_quad(d, {-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, white);
  add_quad(d, {-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, red);
  add_quad(d, {1, 0, -1}, {0, 0, 2}, {0, 2, 0}, green);
  add_sphere(d, {-0.4, 0.4, -0.2}, 0.4, metal);
  add_sphere(d, {0.45, 0.3, 0.3}, 0.3, white);
  add_light(d, QuadLightDesc{{-0.25, 1.98, -0.25}, {0.5, 0, 0}, {0, 0, 0.5}, Rgb(17.f, 12.f, 4.f)});
  return d;
}

}  // namespace vesper::test
