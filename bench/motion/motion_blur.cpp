// Motion blur in Embree, two ways, measured side by side in one run
// (bench/README.md, "vesper_motion_bench"):
//   vertex    one triangle geometry with 2 time steps (a vertex buffer per
//             step, rtcSetGeometryTimeStepCount)
//   instance  the mesh's static BVH in its own scene, instanced once with 2
//             motion transforms (a per-sample transform, interpolated by
//             Embree): what the renderer builds for affine motion
//             (core/rigid_motion.h); deforming meshes keep vertex steps
//   static    the same mesh not moving: the cost without motion blur
// The scene: a displaced UV sphere (2 * segments * (rings - 1) triangles)
// moving by half its radius over the shutter, inside a closed box of 6 quads.
// Rays: from a camera point toward uniform points of the swept region, each
// with a uniform time in [0, 1). Timed: rtcIntersect1 over the ray set on all
// threads, and the BVH build (a motion-blurred frame builds it once); then
// the two motion variants alternately, for a ratio that load changes on a
// shared machine do not bias.
//
// Quick mode for CI smoke runs: --quick (a 32k-triangle mesh, 64k rays).
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "renderer/core/accel.h"
#include "renderer/math/vec.h"

namespace {

using vesper::Vec3;

struct Settings {
  int segments = 512, rings = 257;  // 262,144 triangles
  size_t rays = size_t(1) << 20;
  int threads = 0;
} g_settings;

struct Mesh {
  std::vector<Vec3> positions;
  std::vector<std::array<uint32_t, 3>> triangles;
};

// A UV sphere of radius ~0.5 with a small displacement (so the BVH is not trivial).
Mesh displaced_sphere(int segments, int rings) {
  Mesh m;
  for (int r = 0; r < rings; ++r) {
    const float theta = float(M_PI) * float(r) / float(rings - 1);
    for (int s = 0; s < segments; ++s) {
      const float phi = 2.f * float(M_PI) * float(s) / float(segments);
      const float rad = 0.5f * (1.f + 0.05f * std::sin(7.f * phi) * std::sin(5.f * theta));
      m.positions.push_back(
          Vec3{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)} *
          rad);
    }
  }
  for (int r = 0; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = uint32_t(r * segments + s),
                     b = uint32_t(r * segments + (s + 1) % segments);
      const uint32_t c = a + uint32_t(segments), d = b + uint32_t(segments);
      m.triangles.push_back({a, c, b});
      m.triangles.push_back({b, c, d});
    }
  }
  return m;
}

const Vec3 kMotion{0.25f, 0.f, 0.f};  // displacement over the shutter

void fill_vertices(RTCGeometry g, unsigned slot, const Mesh& m, Vec3 offset) {
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_VERTEX, slot, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.positions.size()));
  for (size_t i = 0; i < m.positions.size(); ++i) {
    v[3 * i] = m.positions[i].x + offset.x;
    v[3 * i + 1] = m.positions[i].y + offset.y;
    v[3 * i + 2] = m.positions[i].z + offset.z;
  }
}

RTCGeometry new_mesh(RTCDevice device, const Mesh& m, int steps) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryTimeStepCount(g, unsigned(steps));
  for (int k = 0; k < steps; ++k) fill_vertices(g, unsigned(k), m, kMotion * float(k));
  auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), m.triangles.size()));
  std::memcpy(idx, m.triangles.data(), m.triangles.size() * sizeof(m.triangles[0]));
  rtcCommitGeometry(g);
  return g;
}

// The closed box [-2, 2]^3 as 6 quads (the room the object moves in).
void add_room(RTCDevice device, RTCScene scene) {
  for (int axis = 0; axis < 3; ++axis) {
    for (float side : {-2.f, 2.f}) {
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4));
      const float uv[4][2] = {{-2, -2}, {2, -2}, {2, 2}, {-2, 2}};
      for (int k = 0; k < 4; ++k) {
        float p[3];
        p[axis] = side;
        p[(axis + 1) % 3] = uv[k][0];
        p[(axis + 2) % 3] = uv[k][1];
        std::memcpy(v + 3 * k, p, sizeof(p));
      }
      auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), 1));
      for (unsigned k = 0; k < 4; ++k) idx[k] = k;
      rtcCommitGeometry(g);
      rtcAttachGeometry(scene, g);
      rtcReleaseGeometry(g);
    }
  }
}

RTCScene new_scene(RTCDevice device) {
  RTCScene s = rtcNewScene(device);
  rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);  // as core/embree_scene.cpp
  rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
  return s;
}

// The top-level scene of one variant; `inner` receives the instanced scene.
RTCScene build(RTCDevice device, const Mesh& m, const std::string& kind, RTCScene& inner) {
  RTCScene top = new_scene(device);
  add_room(device, top);
  RTCGeometry g;
  if (kind == "instance") {
    inner = new_scene(device);
    RTCGeometry mesh = new_mesh(device, m, 1);
    rtcAttachGeometry(inner, mesh);
    rtcReleaseGeometry(mesh);
    rtcCommitScene(inner);
    g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, inner);
    rtcSetGeometryTimeStepCount(g, 2);
    for (unsigned k = 0; k < 2; ++k) {
      const float xfm[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, kMotion.x * float(k), 0, 0};
      rtcSetGeometryTransform(g, k, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    }
    rtcCommitGeometry(g);
  } else {
    g = new_mesh(device, m, kind == "vertex" ? 2 : 1);
  }
  rtcAttachGeometry(top, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(top);
  return top;
}

struct RayRec {
  Vec3 o, d;
  float time;
};

std::vector<RayRec> make_rays(size_t n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<RayRec> rays(n);
  const Vec3 eye{0.1f, 0.2f, -1.9f};
  for (RayRec& r : rays) {
    // Toward the region the sphere sweeps (x in [-0.6, 0.85]).
    const Vec3 target{-0.6f + 1.45f * u(rng), -0.6f + 1.2f * u(rng), -0.6f + 1.2f * u(rng)};
    r.o = eye;
    r.d = normalize(target - eye);
    r.time = u(rng);
  }
  return rays;
}

uint64_t trace(RTCScene scene, const std::vector<RayRec>& rays, int threads) {
  std::atomic<uint64_t> hits{0};
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                        vesper::set_flush_to_zero();
                        RTCIntersectContext ctx;
                        rtcInitIntersectContext(&ctx);
                        uint64_t h = 0;
                        for (size_t i = range.begin(); i < range.end(); ++i) {
                          const RayRec& rec = rays[i];
                          RTCRayHit rh{};
                          rh.ray = {rec.o.x, rec.o.y,  rec.o.z,  0.f,         rec.d.x, rec.d.y,
                                    rec.d.z, rec.time, INFINITY, 0xFFFFFFFFu, 0,       0};
                          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                          rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                          rtcIntersect1(scene, &ctx, &rh);
                          // Hits on the sphere (geometry 6), instanced or not.
                          h += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID &&
                               (rh.hit.instID[0] == 6 || rh.hit.geomID == 6);
                        }
                        hits += h;
                      });
  });
  return hits;
}

struct Shared {
  RTCDevice device = nullptr;
  Mesh mesh;
  std::vector<RayRec> rays;
  std::map<std::string, std::vector<double>> rate, build;  // per repetition, for the summary
};
Shared* g_shared = nullptr;

void BM_Trace(benchmark::State& state, std::string kind) {
  RTCScene inner = nullptr;
  RTCScene scene = build(g_shared->device, g_shared->mesh, kind, inner);
  uint64_t hits = 0;
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) hits = trace(scene, g_shared->rays, g_settings.threads);
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  const double n = double(g_shared->rays.size()) * double(state.iterations());
  g_shared->rate[kind].push_back(n / elapsed.count());
  state.counters["rays/s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
  state.counters["object_hit%"] = 100.0 * double(hits) / double(g_shared->rays.size());
  rtcReleaseScene(scene);
  if (inner) rtcReleaseScene(inner);
}

void BM_Build(benchmark::State& state, std::string kind) {
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    RTCScene inner = nullptr;
    RTCScene scene = build(g_shared->device, g_shared->mesh, kind, inner);
    rtcReleaseScene(scene);
    if (inner) rtcReleaseScene(inner);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    g_shared->build[kind].push_back(elapsed.count());
  }
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

// The machine is shared: load changes between the Google Benchmark runs of
// one variant and the next bias their ratio. Here the two variants alternate,
// one trace each per round, and the ratio is taken per round.
std::vector<double> paired_ratios(int rounds) {
  RTCScene inner_v = nullptr, inner_i = nullptr;
  RTCScene vertex = build(g_shared->device, g_shared->mesh, "vertex", inner_v);
  RTCScene instance = build(g_shared->device, g_shared->mesh, "instance", inner_i);
  auto seconds = [](RTCScene scene) {
    const auto start = std::chrono::steady_clock::now();
    trace(scene, g_shared->rays, g_settings.threads);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::vector<double> ratios;  // instance rate / vertex rate
  for (int r = 0; r < rounds; ++r) {
    const double tv = seconds(vertex), ti = seconds(instance);
    ratios.push_back(tv / ti);
  }
  rtcReleaseScene(vertex);
  rtcReleaseScene(instance);
  rtcReleaseScene(inner_i);
  return ratios;
}

// Medians over every timed run, and the ratios the renderer's choice rests on.
void print_summary(const Shared& s) {
  std::printf("\nmotion blur summary (medians)\n");
  for (const char* kind : {"static", "vertex", "instance"}) {
    std::printf("  %-8s trace %8.2f Mrays/s   build %8.2f ms\n", kind,
                median(s.rate.at(kind)) * 1e-6, median(s.build.at(kind)) * 1e3);
  }
  const double vertex = median(s.rate.at("vertex")), instance = median(s.rate.at("instance"));
  std::printf("  trace rate instance / vertex: %.3f\n", instance / vertex);
  std::printf("  trace rate vertex / static:   %.3f\n", vertex / median(s.rate.at("static")));
  const std::vector<double> paired = paired_ratios(9);
  std::printf(
      "  trace rate instance / vertex, alternating (9 rounds): median %.3f, min %.3f, max %.3f\n",
      median(paired), *std::min_element(paired.begin(), paired.end()),
      *std::max_element(paired.begin(), paired.end()));
  std::printf("  build time instance / vertex: %.3f\n",
              median(s.build.at("instance")) / median(s.build.at("vertex")));
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      g_settings.segments = 128;
      g_settings.rings = 129;
      g_settings.rays = size_t(1) << 16;
    } else {
      args.push_back(argv[i]);
    }
  }
  int n = int(args.size());
  benchmark::Initialize(&n, args.data());
  Shared shared;
  shared.device = rtcNewDevice("");
  shared.mesh = displaced_sphere(g_settings.segments, g_settings.rings);
  shared.rays = make_rays(g_settings.rays);
  g_settings.threads = tbb::this_task_arena::max_concurrency();
  g_shared = &shared;
  std::printf("mesh: %zu triangles, %zu rays, %d threads\n", shared.mesh.triangles.size(),
              shared.rays.size(), g_settings.threads);
  for (const char* kind : {"static", "vertex", "instance"}) {
    benchmark::RegisterBenchmark((std::string("trace/") + kind).c_str(), BM_Trace, kind)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Repetitions(3)
        ->ReportAggregatesOnly(true);
    benchmark::RegisterBenchmark((std::string("build/") + kind).c_str(), BM_Build, kind)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Repetitions(3)
        ->ReportAggregatesOnly(true);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary(shared);
  rtcReleaseDevice(shared.device);
  return 0;
}
