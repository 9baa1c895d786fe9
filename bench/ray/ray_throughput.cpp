// Ray throughput: how much of the machine's raw Embree ray rate the path
// tracer keeps, measured side by side in one run (bench/README.md).
//
// For each scene (the Cornell box from scenes/cornell, and a >= 1M-triangle
// displaced sphere built here) the benchmark measures, with the same thread
// count as the render (all hardware threads, TBB):
//   raw/intersect1/coherent     rtcIntersect1 on primary camera rays, tile order
//   raw/intersect1/incoherent   rtcIntersect1, origins on random surface points,
//                               uniformly random directions
//   raw/intersect1/incoh_volume rtcIntersect1, origins uniform in the geometry bounds
//   raw/occluded1/incoherent    rtcOccluded1 on the incoherent rays (shadow-ray kind)
//   raw/intersect16/coherent    rtcIntersect16 on 4x4 pixel packets: an upper bound
//   accel/intersect/*           the same rays through vesper::Accel::intersect
//   tracer/render               vesper::render: RenderStats::rays / RenderStats::seconds
// and prints a summary with tracer rays/s divided by the raw rates.
//
// The raw Embree scene is built here with the Embree 3 API from the same
// render-space geometry (and the same scene flags and build quality) as the
// scene vesper::build_scene hands to vesper::Accel.
//
// Quick mode for CI smoke runs: --quick or VESPER_BENCH_QUICK=1 (small ray sets,
// a 65k-triangle mesh instead of 1M, 1 spp, one iteration each).
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

#include "renderer/core/accel.h"
#include "renderer/core/ray.h"
#include "renderer/math/vec.h"
#include "renderer/render/render.h"
#include "renderer/sampling/sampler.h"
#include "renderer/sampling/warp.h"
#include "renderer/scene/scene.h"
#include "renderer/scene/scene_description.h"
#include "renderer/scene/scene_loader.h"

namespace {

using vesper::Vec3;
using vesper::Vec3d;

// ---------------------------------------------------------------- settings

struct Settings {
  bool quick = false;
  size_t rays_per_set = size_t(1) << 20;  // rays traced per benchmark iteration
  int mesh_segments = 1024;               // displaced sphere: 2 * segments * (rings - 1) triangles
  int mesh_rings = 513;
  int spp = 8;  // tracer samples per pixel
  int render_iterations = 2;
  double raw_min_time = 0.5;  // seconds per raw measurement
  int threads = 0;            // resolved to all hardware threads
};
Settings g_settings;

// ---------------------------------------------------------------- results

// Accumulated inside one run of a benchmark function.
struct Measure {
  double rays = 0, seconds = 0, hits = 0, cpu_seconds = 0;
  double hit_fraction() const { return rays > 0 ? hits / rays : 0; }
};
// One reported run (a repetition), as captured from Google Benchmark's
// counters by SummaryReporter: runs that only estimate the iteration count
// are never reported, so they do not enter the summary.
struct Sample {
  double rate = 0;             // rays/s
  double hit_fraction = 0;     // raw and accel measurements
  double rays_per_sample = 0;  // tracer
  double cores = 0;            // process CPU time / wall time while measuring
};

// User + system CPU time of the whole process (all threads), in seconds.
double process_cpu_seconds() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}
// results[scene][measurement]: one entry per repetition; the summary takes medians.
std::map<std::string, std::map<std::string, std::vector<Sample>>> g_results;
std::map<std::string, std::string> g_scene_info;

class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  // Colour only on a terminal, like Google Benchmark's own default reporter.
  SummaryReporter() : ConsoleReporter(isatty(fileno(stdout)) ? OO_Color : OO_None) {}
  void ReportRuns(const std::vector<Run>& reports) override {
    for (const Run& r : reports) {
      if (r.run_type != Run::RT_Iteration || r.error_occurred) continue;
      const std::string& name = r.run_name.function_name;  // "<scene>/<measurement>"
      const size_t slash = name.find('/');
      if (slash == std::string::npos) continue;
      auto counter = [&](const char* k) {
        auto it = r.counters.find(k);
        return it == r.counters.end() ? 0.0 : double(it->second.value);
      };
      g_results[name.substr(0, slash)][name.substr(slash + 1)].push_back(
          {counter("rays/s"), counter("hit%") / 100.0, counter("rays/sample"), counter("cores")});
    }
    ConsoleReporter::ReportRuns(reports);
  }
};

// ---------------------------------------------------------------- geometry

// Render-space geometry, exactly as vesper::build_scene hands it to vesper::Accel.
struct RenderGeometry {
  struct Quad {
    Vec3 corner, e1, e2;
  };
  struct Sphere {
    Vec3 center;
    float radius;
  };
  struct Mesh {
    std::vector<Vec3> positions;
    std::vector<std::array<uint32_t, 3>> triangles;
  };
  std::vector<Quad> quads;
  std::vector<Sphere> spheres;
  std::vector<Mesh> meshes;
  size_t primitives() const {
    size_t n = quads.size() + spheres.size();
    for (const auto& m : meshes) n += m.triangles.size();
    return n;
  }
};

RenderGeometry render_geometry(const vesper::SceneDescription& desc, const vesper::Scene& scene) {
  const double inv_scale = 1.0 / scene.unit_scale;
  auto pt = [&](const Vec3d& p) { return Vec3((p - scene.origin) * inv_scale); };
  auto vec = [&](const Vec3d& v) { return Vec3(v * inv_scale); };
  RenderGeometry g;
  for (const auto& s : desc.shapes) {
    if (const auto* q = std::get_if<vesper::QuadShapeDesc>(&s.geometry)) {
      g.quads.push_back({pt(q->corner), vec(q->edge1), vec(q->edge2)});
    } else if (const auto* sp = std::get_if<vesper::SphereShapeDesc>(&s.geometry)) {
      g.spheres.push_back({pt(sp->center), float(sp->radius * inv_scale)});
    } else {
      const auto& m = std::get<vesper::MeshShapeDesc>(s.geometry);
      RenderGeometry::Mesh rm;
      rm.positions.reserve(m.positions.size());
      for (const auto& p : m.positions) rm.positions.push_back(pt(p));
      // Same rule as vesper::Accel: degenerate triangles are dropped.
      for (const auto& t : m.triangles) {
        const Vec3 c =
            cross(rm.positions[t[1]] - rm.positions[t[0]], rm.positions[t[2]] - rm.positions[t[0]]);
        if (length_squared(c) > 0.f && is_finite(c)) rm.triangles.push_back(t);
      }
      if (!rm.triangles.empty()) g.meshes.push_back(std::move(rm));
    }
  }
  for (const auto& l : desc.lights)  // quad emitters are surfaces too
    if (const auto* q = std::get_if<vesper::QuadLightDesc>(&l.light))
      g.quads.push_back({pt(q->corner), vec(q->edge1), vec(q->edge2)});
  std::erase_if(g.quads, [](const RenderGeometry::Quad& q) {
    return !(length_squared(cross(q.e1, q.e2)) > 0.f);
  });
  return g;
}

// ---------------------------------------------------------------- raw Embree

class RawEmbree {
 public:
  explicit RawEmbree(const RenderGeometry& g) {
    device_ = rtcNewDevice("");
    if (!device_) throw std::runtime_error("rtcNewDevice failed");
    scene_ = rtcNewScene(device_);
    // Same flags and quality as vesper::Accel, so the two BVHs are alike.
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    for (const auto& q : g.quads) {
      RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_QUAD);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4));
      const Vec3 p[4] = {q.corner, q.corner + q.e1, q.corner + q.e1 + q.e2, q.corner + q.e2};
      for (int k = 0; k < 4; ++k) std::memcpy(v + 3 * k, &p[k], 3 * sizeof(float));
      auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
          geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), 1));
      for (unsigned k = 0; k < 4; ++k) idx[k] = k;
      attach(geom);
    }
    for (const auto& s : g.spheres) {
      RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
      v[0] = s.center.x;
      v[1] = s.center.y;
      v[2] = s.center.z;
      v[3] = s.radius;
      attach(geom);
    }
    for (const auto& m : g.meshes) {
      RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                 m.positions.data(), 0, sizeof(Vec3), m.positions.size());
      rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                 m.triangles.data(), 0, 3 * sizeof(uint32_t), m.triangles.size());
      attach(geom);
    }
    rtcCommitScene(scene_);
  }
  ~RawEmbree() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  RawEmbree(const RawEmbree&) = delete;
  RawEmbree& operator=(const RawEmbree&) = delete;
  RTCScene scene() const { return scene_; }

 private:
  void attach(RTCGeometry geom) {
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
  }
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

// ---------------------------------------------------------------- ray sets

struct RayRec {
  Vec3 o, d;
};

// Primary camera rays in the renderer's order: sample-major passes over 16x16
// tiles in scanline order; inside a tile, 4x4 pixel blocks (so 16 consecutive
// rays form one packet for rtcIntersect16).
std::vector<RayRec> coherent_rays(const vesper::Scene& scene, size_t count) {
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
                vesper::Sampler smp(99, uint64_t(py) * uint64_t(w) + uint64_t(px), s);
                const vesper::Vec2 j = smp.next2();
                const vesper::Ray r =
                    scene.camera.generate_ray(float(px) + j.x, float(py) + j.y, smp.next2());
                rays.push_back({r.origin, r.dir});
              }
  }
  return rays;
}

// Origins on random surface points (area-weighted over all primitives), moved
// off the surface toward the side the direction leaves from; directions
// uniform on the sphere.
std::vector<RayRec> incoherent_surface_rays(const RenderGeometry& g, size_t count) {
  struct Tri {
    Vec3 a, e1, e2;
  };
  std::vector<Tri> tris;
  for (const auto& q : g.quads) {
    tris.push_back({q.corner, q.e1, q.e2});
    tris.push_back({q.corner + q.e1 + q.e2, -q.e1, -q.e2});
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
    vesper::Sampler smp(1234, i, 0);
    const double pick = double(smp.next1()) * total;
    const size_t k = std::min(size_t(std::upper_bound(cdf.begin(), cdf.end(), pick) - cdf.begin()),
                              cdf.size() - 1);
    const Vec3 d = vesper::sample_uniform_sphere(smp.next2());
    Vec3 p, n;
    if (k < tris.size()) {
      vesper::Vec2 u = smp.next2();
      if (u.x + u.y > 1.f) u = {1.f - u.x, 1.f - u.y};
      const Tri& t = tris[k];
      p = t.a + t.e1 * u.x + t.e2 * u.y;
      n = normalize(cross(t.e1, t.e2));
    } else {
      const auto& s = g.spheres[k - tris.size()];
      n = vesper::sample_uniform_sphere(smp.next2());
      p = s.center + n * s.radius;
    }
    if (dot(n, d) < 0.f) n = -n;
    rays[i] = {vesper::offset_ray_origin(p, n), d};
  });
  return rays;
}

// Origins uniform in the axis-aligned bounds of the geometry; uniform directions.
std::vector<RayRec> incoherent_volume_rays(const RenderGeometry& g, size_t count) {
  Vec3 lo(INFINITY), hi(-INFINITY);
  auto add = [&](const Vec3& p) {
    lo = vesper::min(lo, p);
    hi = vesper::max(hi, p);
  };
  for (const auto& q : g.quads) {
    add(q.corner);
    add(q.corner + q.e1 + q.e2);
    add(q.corner + q.e1);
    add(q.corner + q.e2);
  }
  for (const auto& s : g.spheres) {
    add(s.center - Vec3(s.radius));
    add(s.center + Vec3(s.radius));
  }
  for (const auto& m : g.meshes)
    for (const auto& p : m.positions) add(p);
  std::vector<RayRec> rays(count);
  tbb::parallel_for(size_t(0), count, [&](size_t i) {
    vesper::Sampler smp(5678, i, 0);
    const Vec3 o{lo.x + (hi.x - lo.x) * smp.next1(), lo.y + (hi.y - lo.y) * smp.next1(),
                 lo.z + (hi.z - lo.z) * smp.next1()};
    rays[i] = {o, vesper::sample_uniform_sphere(smp.next2())};
  });
  return rays;
}

// ---------------------------------------------------------------- scenes

struct BenchScene {
  std::string name;
  vesper::SceneDescription desc;
  vesper::Scene scene;
  RenderGeometry geometry;
  std::unique_ptr<RawEmbree> raw;
  std::vector<RayRec> coherent, incoherent, incoherent_volume;
};

// A displaced UV sphere: `segments` around, `rings` from pole to pole, every
// triangle non-degenerate (triangle fans at the poles), outward winding.
vesper::MeshShapeDesc displaced_sphere(Vec3d center, double radius, int segments, int rings) {
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
  vesper::MeshShapeDesc m;
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

// The Cornell room (walls, ceiling light) with a >= 1M-triangle displaced sphere inside.
vesper::SceneDescription dense_mesh_scene(int segments, int rings) {
  vesper::SceneDescription d;
  d.file = "bench:dense-mesh";
  d.film.width = 256;
  d.film.height = 256;
  d.film.filter = vesper::FilterType::Gaussian;
  d.render.spp = 64;
  d.render.max_depth = 8;
  d.render.seed = 1;
  d.camera.from = {0, 1, 3.9};
  d.camera.to = {0, 1, 0};
  d.camera.fov_degrees = 37;
  auto material = [&](const char* name, vesper::Rgb albedo) {
    d.material_names.push_back(name);
    d.materials.push_back(vesper::DiffuseMaterialDesc{albedo});
    return uint32_t(d.materials.size() - 1);
  };
  const uint32_t white = material("white", vesper::Rgb(0.73f));
  const uint32_t red = material("red", vesper::Rgb(0.63f, 0.065f, 0.05f));
  const uint32_t green = material("green", vesper::Rgb(0.14f, 0.45f, 0.091f));
  auto quad = [&](Vec3d c, Vec3d e1, Vec3d e2, uint32_t m) {
    d.shapes.push_back({vesper::QuadShapeDesc{c, e1, e2}, m});
  };
  quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, white);  // floor
  quad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, white);  // ceiling
  quad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, white);  // back
  quad({-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, red);    // left
  quad({1, 0, -1}, {0, 0, 2}, {0, 2, 0}, green);   // right
  d.shapes.push_back({displaced_sphere({0, 0.62, 0}, 0.55, segments, rings), white});
  d.lights.push_back(
      {vesper::QuadLightDesc{
           {-0.24, 1.98, -0.22}, {0.48, 0, 0}, {0, 0, 0.38}, vesper::Rgb(17.f, 12.f, 4.f)},
       ""});
  return d;
}

std::unique_ptr<BenchScene> make_bench_scene(std::string name, vesper::SceneDescription desc) {
  auto bs = std::make_unique<BenchScene>();
  bs->name = std::move(name);
  bs->desc = std::move(desc);
  bs->scene = vesper::build_scene(bs->desc);
  bs->geometry = render_geometry(bs->desc, bs->scene);
  bs->raw = std::make_unique<RawEmbree>(bs->geometry);
  const size_t n = g_settings.rays_per_set;
  bs->coherent = coherent_rays(bs->scene, n);
  bs->incoherent = incoherent_surface_rays(bs->geometry, n);
  bs->incoherent_volume = incoherent_volume_rays(bs->geometry, n);
  g_scene_info[bs->name] =
      std::to_string(bs->geometry.primitives()) +
      " primitives (accel: " + std::to_string(bs->scene.accel->primitive_count()) + "), film " +
      std::to_string(bs->scene.film.width) + "x" + std::to_string(bs->scene.film.height) +
      ", max_depth " + std::to_string(bs->scene.render.max_depth);
  return bs;
}

// ---------------------------------------------------------------- tracing loops

constexpr size_t kChunk = 4096;  // rays per TBB task (a multiple of 16)

template <typename Body>  // Body(begin, end) -> hits in [begin, end)
uint64_t parallel_trace(size_t count, Body body) {
  std::atomic<uint64_t> hits{0};
  tbb::task_arena arena(g_settings.threads);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, count, kChunk),
        [&](const tbb::blocked_range<size_t>& r) {
          vesper::set_flush_to_zero();
          hits += body(r.begin(), r.end());
        },
        tbb::simple_partitioner());
  });
  return hits;
}

inline void fill_ray(RTCRay& r, const RayRec& rec) {
  r.org_x = rec.o.x;
  r.org_y = rec.o.y;
  r.org_z = rec.o.z;
  r.tnear = 0.f;
  r.dir_x = rec.d.x;
  r.dir_y = rec.d.y;
  r.dir_z = rec.d.z;
  r.time = 0.f;
  r.tfar = INFINITY;
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
}

uint64_t raw_intersect1(RTCScene scene, const std::vector<RayRec>& rays) {
  return parallel_trace(rays.size(), [&](size_t b, size_t e) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    uint64_t hits = 0;
    for (size_t i = b; i < e; ++i) {
      RTCRayHit rh;
      fill_ray(rh.ray, rays[i]);
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &ctx, &rh);
      hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    return hits;
  });
}

uint64_t raw_occluded1(RTCScene scene, const std::vector<RayRec>& rays) {
  return parallel_trace(rays.size(), [&](size_t b, size_t e) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    uint64_t hits = 0;
    for (size_t i = b; i < e; ++i) {
      RTCRay r;
      fill_ray(r, rays[i]);
      rtcOccluded1(scene, &ctx, &r);
      hits += r.tfar < 0.f;
    }
    return hits;
  });
}

uint64_t raw_intersect16(RTCScene scene, const std::vector<RayRec>& rays) {
  return parallel_trace(rays.size(), [&](size_t b, size_t e) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) int valid[16];
    alignas(64) RTCRayHit16 rh;
    uint64_t hits = 0;
    for (size_t i = b; i < e; i += 16) {
      const int n = int(std::min<size_t>(16, e - i));
      for (int k = 0; k < 16; ++k) {
        valid[k] = k < n ? -1 : 0;
        const RayRec& rec = rays[i + size_t(std::min(k, n - 1))];
        rh.ray.org_x[k] = rec.o.x;
        rh.ray.org_y[k] = rec.o.y;
        rh.ray.org_z[k] = rec.o.z;
        rh.ray.tnear[k] = 0.f;
        rh.ray.dir_x[k] = rec.d.x;
        rh.ray.dir_y[k] = rec.d.y;
        rh.ray.dir_z[k] = rec.d.z;
        rh.ray.time[k] = 0.f;
        rh.ray.tfar[k] = INFINITY;
        rh.ray.mask[k] = 0xFFFFFFFFu;
        rh.ray.id[k] = unsigned(k);
        rh.ray.flags[k] = 0;
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect16(valid, scene, &ctx, &rh);
      for (int k = 0; k < n; ++k) hits += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    }
    return hits;
  });
}

uint64_t accel_intersect(const vesper::Accel& accel, const std::vector<RayRec>& rays) {
  return parallel_trace(rays.size(), [&](size_t b, size_t e) {
    uint64_t hits = 0;
    for (size_t i = b; i < e; ++i)
      hits += accel.intersect(vesper::Ray{rays[i].o, rays[i].d}).has_value();
    return hits;
  });
}

// ---------------------------------------------------------------- benchmarks

using Clock = std::chrono::steady_clock;

template <typename Run>  // Run() -> hits; traces `rays` rays
void bench_rays(benchmark::State& state, size_t rays, Run run) {
  Measure m;
  for (auto _ : state) {
    const double c0 = process_cpu_seconds();
    const auto t0 = Clock::now();
    const uint64_t hits = run();
    const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    m.cpu_seconds += process_cpu_seconds() - c0;
    state.SetIterationTime(dt);
    benchmark::DoNotOptimize(hits);
    m.rays += double(rays);
    m.seconds += dt;
    m.hits += double(hits);
  }
  state.counters["rays/s"] = benchmark::Counter(m.rays, benchmark::Counter::kIsRate);
  state.counters["hit%"] = 100.0 * m.hit_fraction();
  state.counters["cores"] = m.seconds > 0 ? m.cpu_seconds / m.seconds : 0;
  state.counters["threads"] = g_settings.threads;
}

void bench_render(benchmark::State& state, const BenchScene& bs) {
  vesper::RenderOptions opt;
  opt.threads = g_settings.threads;
  opt.spp = g_settings.spp;
  opt.aovs = std::vector<vesper::Aov>{};
  Measure m;
  double samples = 0;
  for (auto _ : state) {
    const double c0 = process_cpu_seconds();
    const vesper::RenderResult r = vesper::render(bs.scene, opt);
    m.cpu_seconds += process_cpu_seconds() - c0;
    state.SetIterationTime(r.stats.seconds);
    m.rays += double(r.stats.rays);
    m.seconds += r.stats.seconds;
    samples += double(r.stats.camera_samples);
    benchmark::DoNotOptimize(r.image.pixels.data());
  }
  state.counters["rays/s"] = benchmark::Counter(m.rays, benchmark::Counter::kIsRate);
  state.counters["rays/sample"] = samples > 0 ? m.rays / samples : 0;
  state.counters["cores"] = m.seconds > 0 ? m.cpu_seconds / m.seconds : 0;
  state.counters["spp"] = g_settings.spp;
  state.counters["threads"] = g_settings.threads;
}

void register_scene(const BenchScene& bs) {
  const std::string& s = bs.name;
  auto reg = [&](const std::string& what, size_t rays, auto run) {
    auto* b = benchmark::RegisterBenchmark(
        (s + "/" + what).c_str(), [=](benchmark::State& st) { bench_rays(st, rays, run); });
    b->UseManualTime()->Unit(benchmark::kMillisecond);
    if (g_settings.quick)
      b->Iterations(1);
    else
      b->MinTime(g_settings.raw_min_time);
  };
  const RTCScene rs = bs.raw->scene();
  const vesper::Accel* accel = bs.scene.accel.get();
  const auto *coh = &bs.coherent, *inc = &bs.incoherent, *vol = &bs.incoherent_volume;
  reg("raw/intersect1/coherent", coh->size(), [=] { return raw_intersect1(rs, *coh); });
  reg("raw/intersect1/incoherent", inc->size(), [=] { return raw_intersect1(rs, *inc); });
  reg("raw/intersect1/incoh_volume", vol->size(), [=] { return raw_intersect1(rs, *vol); });
  reg("raw/occluded1/incoherent", inc->size(), [=] { return raw_occluded1(rs, *inc); });
  reg("raw/intersect16/coherent", coh->size(), [=] { return raw_intersect16(rs, *coh); });
  reg("accel/intersect/coherent", coh->size(), [=] { return accel_intersect(*accel, *coh); });
  reg("accel/intersect/incoherent", inc->size(), [=] { return accel_intersect(*accel, *inc); });
  auto* r = benchmark::RegisterBenchmark((s + "/tracer/render").c_str(),
                                         [&bs](benchmark::State& st) { bench_render(st, bs); });
  r->UseManualTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(g_settings.quick ? 1 : g_settings.render_iterations);
}

// ---------------------------------------------------------------- summary

void print_summary(const std::vector<std::string>& scenes) {
  // Median over repetitions (robust to a burst of load from other processes).
  auto median = [&](const std::string& s, const std::string& what, auto f) -> double {
    auto it = g_results[s].find(what);
    if (it == g_results[s].end() || it->second.empty()) return 0.0;
    std::vector<double> v;
    for (const Sample& m : it->second) v.push_back(f(m));
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  };
  auto rate = [&](const std::string& s, const std::string& what) {
    return median(s, what, [](const Sample& m) { return m.rate; });
  };
  auto cell = [](double v, const char* fmt) {
    char buf[64];
    if (v > 0)
      std::snprintf(buf, sizeof buf, fmt, v);
    else
      std::snprintf(buf, sizeof buf, "-");
    return std::string(buf);
  };
  size_t reps = 0;
  for (auto& [scene, m] : g_results)
    for (auto& [what, v] : m) reps = std::max(reps, v.size());
  std::printf(
      "\n=== Ray throughput summary (%d threads, Embree %s, median of %zu repetition(s)%s) ===\n",
      g_settings.threads, RTC_VERSION_STRING, reps,
      g_settings.quick ? ", QUICK MODE: smoke test only, figures not representative" : "");
  for (const auto& s : scenes) std::printf("  %-11s %s\n", s.c_str(), g_scene_info[s].c_str());
  std::printf("\n%-44s", "Mrays/s");
  for (const auto& s : scenes) std::printf("%16s", s.c_str());
  std::printf("\n");
  const char* rows[][2] = {
      {"raw/intersect1/coherent", "raw rtcIntersect1, coherent (camera)"},
      {"raw/intersect1/incoherent", "raw rtcIntersect1, incoherent (surface)"},
      {"raw/intersect1/incoh_volume", "raw rtcIntersect1, incoherent (volume)"},
      {"raw/occluded1/incoherent", "raw rtcOccluded1, incoherent (surface)"},
      {"raw/intersect16/coherent", "raw rtcIntersect16, coherent (upper bound)"},
      {"accel/intersect/coherent", "vesper::Accel::intersect, coherent"},
      {"accel/intersect/incoherent", "vesper::Accel::intersect, incoherent"},
      {"tracer/render", "path tracer (vesper::render)"},
  };
  for (const auto& row : rows) {
    std::printf("%-44s", row[1]);
    for (const auto& s : scenes) std::printf("%16s", cell(rate(s, row[0]) / 1e6, "%.2f").c_str());
    std::printf("\n");
  }
  std::printf("%-44s", "hit fraction: coherent / incoherent");
  for (const auto& s : scenes) {
    auto hf = [&](const char* k) {
      return median(s, k, [](const Sample& m) { return m.hit_fraction; });
    };
    std::printf("%16s", (cell(hf("raw/intersect1/coherent"), "%.2f") + " / " +
                         cell(hf("raw/intersect1/incoherent"), "%.2f"))
                            .c_str());
  }
  std::printf("\n%-44s", "cores busy: raw coh / raw incoh / tracer");
  for (const auto& s : scenes) {
    auto cores = [&](const char* k) {
      return median(s, k, [](const Sample& m) { return m.cores; });
    };
    std::printf("%16s", (cell(cores("raw/intersect1/coherent"), "%.1f") + "/" +
                         cell(cores("raw/intersect1/incoherent"), "%.1f") + "/" +
                         cell(cores("tracer/render"), "%.1f"))
                            .c_str());
  }
  std::printf("\n%-44s", "tracer rays per camera sample");
  for (const auto& s : scenes)
    std::printf(
        "%16s",
        cell(median(s, "tracer/render", [](const Sample& m) { return m.rays_per_sample; }), "%.2f")
            .c_str());
  std::printf("\n\nratio (share of the physical limit the tracer keeps)\n");
  const char* ratios[][3] = {
      {"tracer/render", "raw/intersect1/incoherent", "tracer / raw incoherent (surface)"},
      {"tracer/render", "raw/intersect1/incoh_volume", "tracer / raw incoherent (volume)"},
      {"tracer/render", "raw/intersect1/coherent", "tracer / raw coherent"},
      {"tracer/render", "raw/intersect16/coherent", "tracer / raw coherent packets (16)"},
      {"accel/intersect/incoherent", "raw/intersect1/incoherent",
       "Accel wrapper / raw, incoherent"},
      {"accel/intersect/coherent", "raw/intersect1/coherent", "Accel wrapper / raw, coherent"},
  };
  for (const auto& row : ratios) {
    std::printf("%-44s", row[2]);
    for (const auto& s : scenes) {
      const double num = rate(s, row[0]), den = rate(s, row[1]);
      std::printf("%16s", cell(num > 0 && den > 0 ? num / den : 0, "%.3f").c_str());
    }
    std::printf("\n");
  }
  std::fflush(stdout);
}

bool env_quick() {
  const char* v = std::getenv("VESPER_BENCH_QUICK");
  return v && *v && std::strcmp(v, "0") != 0;
}

}  // namespace

int main(int argc, char** argv) {
  // --quick is ours; strip it before Google Benchmark sees the arguments.
  std::vector<char*> args;
  bool quick = env_quick();
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0)
      quick = true;
    else
      args.push_back(argv[i]);
  }
  // Defaults: 3 repetitions, randomly interleaved, so that load from other
  // processes hits raw and tracer measurements alike; the summary takes medians.
  // Both can be overridden on the command line.
  auto has_flag = [&](const char* prefix) {
    return std::any_of(args.begin(), args.end(), [&](const char* a) {
      return std::strncmp(a, prefix, std::strlen(prefix)) == 0;
    });
  };
  static char reps_flag[] = "--benchmark_repetitions=3";
  static char interleave_flag[] = "--benchmark_enable_random_interleaving=true";
  if (!quick && !has_flag("--benchmark_repetitions")) args.push_back(reps_flag);
  if (!quick && !has_flag("--benchmark_enable_random_interleaving"))
    args.push_back(interleave_flag);
  int nargs = int(args.size());
  if (quick) {
    g_settings.quick = true;
    g_settings.rays_per_set = size_t(1) << 14;
    g_settings.mesh_segments = 256;
    g_settings.mesh_rings = 129;
    g_settings.spp = 1;
  }
  g_settings.threads =
      tbb::this_task_arena::max_concurrency();  // what vesper::render uses for threads = 0

  benchmark::Initialize(&nargs, args.data());
  if (benchmark::ReportUnrecognizedArguments(nargs, args.data())) return 1;

  std::vector<std::unique_ptr<BenchScene>> scenes;
  try {
    const auto t0 = Clock::now();
    scenes.push_back(make_bench_scene("cornell", vesper::load_scene(std::string(VESPER_SOURCE_DIR) +
                                                                    "/scenes/cornell/scene.json")));
    scenes.push_back(make_bench_scene(
        "dense-mesh", dense_mesh_scene(g_settings.mesh_segments, g_settings.mesh_rings)));
    std::fprintf(stderr, "scenes built and ray sets generated in %.2f s\n",
                 std::chrono::duration<double>(Clock::now() - t0).count());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vesper_bench: %s\n", e.what());
    return 1;
  }
  std::vector<std::string> names;
  for (const auto& s : scenes) {
    register_scene(*s);
    names.push_back(s->name);
  }
  SummaryReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  print_summary(names);
  return 0;
}
