#include "bench/ray/raw_rays.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace vesper::bench {
namespace {

constexpr size_t kChunk = 4096;  // rays per TBB task (a multiple of 16)

template <typename Body>  // Body(begin, end) -> hits in [begin, end)
uint64_t parallel_trace(size_t count, int threads, Body body) {
  std::atomic<uint64_t> hits{0};
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, count, kChunk),
        [&](const tbb::blocked_range<size_t>& r) {
          set_flush_to_zero();
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

// One single-ray query per ray; Query(ctx, ray) -> whether it hit.
template <typename Query>
uint64_t count_single_ray_hits(const std::vector<RayRec>& rays, int threads, Query query) {
  return parallel_trace(rays.size(), threads, [&](size_t b, size_t e) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    uint64_t hits = 0;
    for (size_t i = b; i < e; ++i) hits += query(ctx, rays[i]);
    return hits;
  });
}

}  // namespace

uint64_t raw_intersect1(RTCScene scene, const std::vector<RayRec>& rays, int threads) {
  return count_single_ray_hits(rays, threads, [&](RTCIntersectContext& ctx, const RayRec& rec) {
    RTCRayHit rh;
    fill_ray(rh.ray, rec);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  });
}

uint64_t raw_occluded1(RTCScene scene, const std::vector<RayRec>& rays, int threads) {
  return count_single_ray_hits(rays, threads, [&](RTCIntersectContext& ctx, const RayRec& rec) {
    RTCRay r;
    fill_ray(r, rec);
    rtcOccluded1(scene, &ctx, &r);
    return r.tfar < 0.f;
  });
}

uint64_t raw_intersect16(RTCScene scene, const std::vector<RayRec>& rays, int threads) {
  return parallel_trace(rays.size(), threads, [&](size_t b, size_t e) {
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

uint64_t accel_intersect(const Accel& accel, const std::vector<RayRec>& rays, int threads) {
  return parallel_trace(rays.size(), threads, [&](size_t b, size_t e) {
    uint64_t hits = 0;
    for (size_t i = b; i < e; ++i) hits += accel.intersect(Ray{rays[i].o, rays[i].d}).has_value();
    return hits;
  });
}

}  // namespace vesper::bench
