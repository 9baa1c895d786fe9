#include "bench/ray/scenes.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "renderer/sampling/sampler.h"
#include "renderer/sampling/warp.h"

namespace vesper::bench {
namespace {

// Primary camera rays in the renderer's order: sample-major passes over 16x16
// tiles in scanline order; inside a tile, 4x4 pixel blocks (so 16 consecutive
// rays form one packet for rtcIntersect16).
std::vector<RayRec> coherent_rays(const Scene& scene, size_t count) {
  const int w = scene.camera.width, h = scene.camera.height;
  std::vector<RayRec> rays;
  rays.reserve(count);
  for (uint64_t s = 0; rays.size() < count; ++s) {
    for (int ty = 0; ty < h && rays.size() < count; ty += 16)
      for (int tx = 0; tx < w && rays.size() < count; tx += 16)
        for (int by = ty; by < std::min(h, ty + 16); by += 4)
          for (int bx = tx; bx < std::min(w, tx + 16); bx += 4)
            for (int y = by; y < by + 4; ++y)
              for (int x = bx; x < bx + 4; ++x) {
                if (rays.size() >= count) break;
                // Pixels past the film edge repeat the edge pixel so packets stay full.
                const int px = std::min(x, w - 1), py = std::min(y, h - 1);
                Sampler smp(99, uint64_t(py) * uint64_t(w) + uint64_t(px), s);
                const Vec2 j = smp.next2();
                const Ray r =
                    scene.camera.generate_ray(float(px) + j.x, float(py) + j.y, smp.next2());
                rays.push_back({r.origin, r.dir});
              }
  }
  return rays;
}

// Origins on random surface points (area-weighted over all primitives), moved
// off the surface toward the side the direction leaves from; directions
// uniform on the sphere.
std::vector<RayRec> incoherent_surface_rays(const AccelGeometry& g, size_t count) {
  struct Tri {
    Vec3 a, e1, e2;
  };
  std::vector<Tri> tris;
  for (const auto& q : g.quads) {
    tris.push_back({q.corner, q.edge1, q.edge2});
    tris.push_back({q.corner + q.edge1 + q.edge2, -q.edge1, -q.edge2});
  }
  for (const auto& m : g.meshes)
    for (const auto& t : m.triangles)
      tris.push_back({m.positions[t[0]], m.positions[t[1]] - m.positions[t[0]],
                      m.positions[t[2]] - m.positions[t[0]]});
  std::vector<double> cdf;
  cdf.reserve(tris.size() + g.spheres.size());
  double total = 0;
  for (const auto& t : tris) cdf.push_back(total += 0.5 * double(length(cross(t.e1, t.e2))));
  for (const auto& s : g.spheres)
    cdf.push_back(total += 4.0 * std::numbers::pi * double(s.radius) * s.radius);

  std::vector<RayRec> rays(count);
  tbb::parallel_for(size_t(0), count, [&](size_t i) {
    Sampler smp(1234, i, 0);
    const double pick = double(smp.next1()) * total;
    const size_t k = std::min(size_t(std::upper_bound(cdf.begin(), cdf.end(), pick) - cdf.begin()),
                              cdf.size() - 1);
    const Vec3 d = sample_uniform_sphere(smp.next2());
    Vec3 p, n;
    if (k < tris.size()) {
      Vec2 u = smp.next2();
      if (u.x + u.y > 1.f) u = {1.f - u.x, 1.f - u.y};
      const Tri& t = tris[k];
      p = t.a + t.e1 * u.x + t.e2 * u.y;
      n = normalize(cross(t.e1, t.e2));
    } else {
      const auto& s = g.spheres[k - tris.size()];
      n = sample_uniform_sphere(smp.next2());
      p = s.center + n * s.radius;
    }
    if (dot(n, d) < 0.f) n = -n;
    rays[i] = {offset_ray_origin(p, n), d};
  });
  return rays;
}

// Origins uniform in the axis-aligned bounds of the geometry; uniform directions.
std::vector<RayRec> incoherent_volume_rays(const AccelGeometry& g, size_t count) {
  Vec3 lo(INFINITY), hi(-INFINITY);
  auto add = [&](const Vec3& p) {
    lo = min(lo, p);
    hi = max(hi, p);
  };
  for (const auto& q : g.quads) {
    add(q.corner);
    add(q.corner + q.edge1 + q.edge2);
    add(q.corner + q.edge1);
    add(q.corner + q.edge2);
  }
  for (const auto& s : g.spheres) {
    add(s.center - Vec3(s.radius));
    add(s.center + Vec3(s.radius));
  }
  for (const auto& m : g.meshes)
    for (const auto& p : m.positions) add(p);
  std::vector<RayRec> rays(count);
  tbb::parallel_for(size_t(0), count, [&](size_t i) {
    Sampler smp(5678, i, 0);
    const Vec3 o{lo.x + (hi.x - lo.x) * smp.next1(), lo.y + (hi.y - lo.y) * smp.next1(),
                 lo.z + (hi.z - lo.z) * smp.next1()};
    rays[i] = {o, sample_uniform_sphere(smp.next2())};
  });
  return rays;
}

// A displaced UV sphere: `segments` around, `rings` from pole to pole, every
// triangle non-degenerate (triangle fans at the poles), outward winding.
MeshShapeDesc displaced_sphere(Vec3d center, double radius, int segments, int rings) {
  auto r_of = [&](double theta, double phi) {
    // Integer frequencies in theta: the displacement vanishes at the poles.
    return radius * (1.0 + 0.06 * std::sin(7 * theta) * std::cos(5 * phi) +
                     0.03 * std::sin(23 * theta) * std::sin(19 * phi) +
                     0.012 * std::sin(61 * theta) * std::cos(67 * phi + 0.5));
  };
  auto pos = [&](double theta, double phi) {
    const double r = r_of(theta, phi);
    return center + Vec3d(std::sin(theta) * std::cos(phi), std::cos(theta),
                          std::sin(theta) * std::sin(phi)) *
                        r;
  };
  MeshShapeDesc m;
  m.source = "procedural displaced sphere";
  const double pi = std::numbers::pi;
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j)
      m.positions.push_back(pos(pi * i / rings, 2 * pi * j / segments));
  const uint32_t north = uint32_t(m.positions.size());
  m.positions.push_back(center + Vec3d(0, radius, 0));
  const uint32_t south = uint32_t(m.positions.size());
  m.positions.push_back(center - Vec3d(0, radius, 0));
  auto v = [&](int ring, int seg) { return uint32_t((ring - 1) * segments + (seg % segments)); };
  for (int j = 0; j < segments; ++j) m.triangles.push_back({north, v(1, j + 1), v(1, j)});
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      m.triangles.push_back({v(i, j), v(i, j + 1), v(i + 1, j)});
      m.triangles.push_back({v(i, j + 1), v(i + 1, j + 1), v(i + 1, j)});
    }
  for (int j = 0; j < segments; ++j)
    m.triangles.push_back({v(rings - 1, j), v(rings - 1, j + 1), south});
  return m;
}

}  // namespace

// The Cornell room (walls, ceiling light) with a >= 1M-triangle displaced sphere inside.
SceneDescription dense_mesh_scene(int segments, int rings) {
  SceneDescription d;
  d.file = "bench:dense-mesh";
  d.film.width = 256;
  d.film.height = 256;
  d.film.filter = FilterType::Gaussian;
  d.render.spp = 64;
  d.render.max_depth = 8;
  d.render.seed = 1;
  d.camera.from = {0, 1, 3.9};
  d.camera.to = {0, 1, 0};
  d.camera.fov_degrees = 37;
  auto material = [&](const char* name, Rgb albedo) {
    d.material_names.push_back(name);
    d.materials.push_back(DiffuseMaterialDesc{albedo});
    return uint32_t(d.materials.size() - 1);
  };
  const uint32_t white = material("white", Rgb(0.73f));
  const uint32_t red = material("red", Rgb(0.63f, 0.065f, 0.05f));
  const uint32_t green = material("green", Rgb(0.14f, 0.45f, 0.091f));
  auto quad = [&](Vec3d c, Vec3d e1, Vec3d e2, uint32_t m) {
    d.shapes.push_back({QuadShapeDesc{c, e1, e2}, m, {}});
  };
  quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, white);  // floor
  quad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, white);  // ceiling
  quad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, white);  // back
  quad({-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, red);    // left
  quad({1, 0, -1}, {0, 0, 2}, {0, 2, 0}, green);   // right
  d.shapes.push_back({displaced_sphere({0, 0.62, 0}, 0.55, segments, rings), white, {}});
  d.lights.push_back(
      {QuadLightDesc{{-0.24, 1.98, -0.22}, {0.48, 0, 0}, {0, 0, 0.38}, Rgb(17.f, 12.f, 4.f)}, ""});
  return d;
}

std::unique_ptr<BenchScene> make_bench_scene(std::string name, SceneDescription desc,
                                             size_t rays_per_set) {
  auto bs = std::make_unique<BenchScene>();
  bs->name = std::move(name);
  bs->desc = std::move(desc);
  bs->scene = build_scene(bs->desc);
  const AccelGeometry& geometry = bs->scene.accel->geometry();
  bs->raw = std::make_unique<EmbreeScene>(geometry);
  bs->coherent = coherent_rays(bs->scene, rays_per_set);
  bs->incoherent = incoherent_surface_rays(geometry, rays_per_set);
  bs->incoherent_volume = incoherent_volume_rays(geometry, rays_per_set);
  bs->info = std::to_string(bs->scene.accel->primitive_count()) + " primitives, film " +
             std::to_string(bs->scene.film.width) + "x" + std::to_string(bs->scene.film.height) +
             ", max_depth " + std::to_string(bs->scene.render.max_depth);
  return bs;
}

}  // namespace vesper::bench
