#include <algorithm>
#include <cmath>
#include <limits>

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

// World-space bounds of everything with a position, to pick the unit scale.
struct Bounds {
  Vec3d lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
  void add(const Vec3d& p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  void add_parallelogram(const Vec3d& corner, const Vec3d& e1, const Vec3d& e2) {
    add(corner);
    add(corner + e1);
    add(corner + e2);
    add(corner + e1 + e2);
  }
  bool empty() const { return lo.x > hi.x; }
};

Bounds scene_bounds(const SceneDescription& d) {
  Bounds b;
  b.add(d.camera.from);
  for (const auto& s : d.shapes) {
    std::visit(
        [&](const auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, QuadShapeDesc>) {
            b.add_parallelogram(g.corner, g.edge1, g.edge2);
          } else if constexpr (std::is_same_v<T, SphereShapeDesc>) {
            b.add(g.center - Vec3d(g.radius));
            b.add(g.center + Vec3d(g.radius));
          } else {
            for (const auto& p : g.positions) b.add(p);
          }
        },
        s.geometry);
  }
  for (const auto& l : d.lights) {
    std::visit(
        [&](const auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, QuadLightDesc>) {
            b.add_parallelogram(g.corner, g.edge1, g.edge2);
          } else if constexpr (std::is_same_v<T, PointLightDesc> ||
                               std::is_same_v<T, SpotLightDesc>) {
            b.add(g.position);
          }
        },
        l.light);
  }
  for (const auto& m : d.media) {
    if (const auto* h = std::get_if<HomogeneousMediumDesc>(&m.medium)) {
      if (h->bounds) {
        b.add(h->bounds->min);
        b.add(h->bounds->max);
      }
    } else if (const auto* v = std::get_if<VdbMediumDesc>(&m.medium); v && v->density) {
      const IndexBox box = v->density->active_box();
      if (box.empty()) continue;
      for (int c = 0; c < 8; ++c) {
        const Vec3d ip{double((c & 1) ? box.max[0] + 1 : box.min[0] - 1),
                       double((c & 2) ? box.max[1] + 1 : box.min[1] - 1),
                       double((c & 4) ? box.max[2] + 1 : box.min[2] - 1)};
        b.add(v->transform.apply_point(v->density->index_to_world().apply_point(ip)));
      }
    }
  }
  return b;
}

}  // namespace

Scene build_scene(const SceneDescription& desc, const SceneBuildOptions& options) {
  Scene scene;
  scene.film = desc.film;
  scene.render = desc.render;
  scene.content_hash = desc.content_hash;
  scene.origin = desc.camera.from;

  const Bounds b = scene_bounds(desc);
  double radius = 0;
  for (int c = 0; c < 8; ++c) {
    const Vec3d corner{(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y,
                       (c & 4) ? b.hi.z : b.lo.z};
    radius = std::max(radius, length(corner - scene.origin));
  }
  scene.unit_scale = radius > 0 && std::isfinite(radius) ? radius : 1.0;
  const double inv_scale = 1.0 / scene.unit_scale;
  auto to_render = [&](const Vec3d& p) { return Vec3((p - scene.origin) * inv_scale); };
  auto vec_to_render = [&](const Vec3d& v) { return Vec3(v * inv_scale); };
  scene.radius = float(radius * inv_scale);
  if (!(scene.radius > 0.f)) scene.radius = 1.f;

  // Camera.
  const CameraDesc& cd = desc.camera;
  Camera& cam = scene.camera;
  cam.position = Vec3(0.f);
  const Vec3d fwd = normalize(cd.to - cd.from);
  const Vec3d right = normalize(cross(fwd, cd.up));
  cam.forward = Vec3(fwd);
  cam.right = Vec3(right);
  cam.up = Vec3(cross(right, fwd));
  cam.width = desc.film.width;
  cam.height = desc.film.height;
  const float t = float(std::tan(cd.fov_degrees * 0.5 * M_PI / 180.0));
  const float aspect = float(desc.film.width) / float(desc.film.height);
  if (aspect >= 1.f) {
    cam.tan_half_y = t;
    cam.tan_half_x = t * aspect;
  } else {
    cam.tan_half_x = t;
    cam.tan_half_y = t / aspect;
  }
  cam.lens_radius = float(0.5 * cd.aperture * inv_scale);
  cam.focus_distance = float(cd.focus_distance * inv_scale);

  for (const auto& m : desc.materials) scene.materials.push_back(make_bsdf(m));

  std::vector<AccelQuad> quads;
  std::vector<AccelSphere> spheres;
  std::vector<AccelMesh> meshes;
  for (const auto& s : desc.shapes) {
    std::visit(
        [&](const auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, QuadShapeDesc>) {
            quads.push_back({to_render(g.corner), vec_to_render(g.edge1), vec_to_render(g.edge2),
                             s.material, -1});
          } else if constexpr (std::is_same_v<T, SphereShapeDesc>) {
            spheres.push_back({to_render(g.center), float(g.radius * inv_scale), s.material});
          } else {
            AccelMesh m;
            m.positions.reserve(g.positions.size());
            for (const auto& p : g.positions) m.positions.push_back(to_render(p));
            m.triangles = g.triangles;
            m.material = s.material;
            meshes.push_back(std::move(m));
          }
        },
        s.geometry);
  }

  // Light power must not depend on the unit scale: intensities fall off with
  // distance squared, so they scale with 1/unit_scale^2 in render space.
  const float inv_scale2 = float(inv_scale * inv_scale);
  for (const auto& ld : desc.lights) {
    const uint32_t index = uint32_t(scene.lights.size());
    std::visit(
        [&](const auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, QuadLightDesc>) {
            QuadLight q;
            q.corner = to_render(g.corner);
            q.edge1 = vec_to_render(g.edge1);
            q.edge2 = vec_to_render(g.edge2);
            const Vec3 c = cross(q.edge1, q.edge2);
            q.area = length(c);
            q.normal = q.area > 0.f ? c / q.area : Vec3(0, 0, 1);
            q.radiance = g.radiance;
            scene.lights.push_back(q);
            // The emitter is also a surface that camera and BSDF rays can hit.
            quads.push_back({q.corner, q.edge1, q.edge2, 0, int32_t(index)});
          } else if constexpr (std::is_same_v<T, PointLightDesc>) {
            scene.lights.push_back(PointLight{to_render(g.position), g.intensity * inv_scale2});
          } else if constexpr (std::is_same_v<T, SpotLightDesc>) {
            SpotLight sp;
            sp.position = to_render(g.position);
            sp.direction = normalize(Vec3(g.direction));
            sp.intensity = g.intensity * inv_scale2;
            sp.cos_cone = float(std::cos(g.cone_angle * M_PI / 180.0));
            sp.cos_falloff_start = float(std::cos(g.falloff_start * M_PI / 180.0));
            scene.lights.push_back(sp);
          } else if constexpr (std::is_same_v<T, SunLightDesc>) {
            SunLight sun;
            sun.direction = normalize(Vec3(g.direction));
            sun.irradiance = g.irradiance;
            const double half = 0.5 * g.angle * M_PI / 180.0;
            sun.cos_max = half > 0 ? float(std::cos(half)) : 1.f;
            if (sun.cos_max >= 1.f) sun.cos_max = 1.f;
            sun.frame = Frame::from_normal(sun.direction);
            const double sin2 = std::sin(half) * std::sin(half);
            sun.radiance = sun.is_delta() ? Rgb{} : g.irradiance * float(1.0 / (M_PI * sin2));
            scene.lights.push_back(sun);
            if (!sun.is_delta()) scene.infinite_lights.push_back(index);
          } else {
            EnvironmentLight env;
            const float scale = float(g.scale);
            if (g.image) {
              std::vector<Rgb> px = g.image->pixels;
              for (auto& c : px) c *= scale;
              env.map = EnvironmentLight::make_map(g.image->width, g.image->height, std::move(px));
            } else {
              env.constant = g.radiance * scale;
            }
            const double rot = g.rotation * M_PI / 180.0;
            env.cos_rot = float(std::cos(rot));
            env.sin_rot = float(std::sin(rot));
            scene.lights.push_back(std::move(env));
            scene.infinite_lights.push_back(index);
          }
        },
        ld.light);
    scene.light_groups.push_back(ld.group);
  }
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
  scene.light_sampler = LightSampler(scene.lights, scene.radius);
  scene.media = build_media(desc, scene.origin, scene.unit_scale, options.media);
  scene.accel = std::make_unique<Accel>(std::move(quads), std::move(spheres), std::move(meshes));
  return scene;
}

}  // namespace vesper
