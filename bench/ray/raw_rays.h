#pragma once
// The timed tracing loops of the ray-throughput benchmark: raw Embree queries
// against an EmbreeScene, and the same rays through vesper::Accel. Each runs
// on `threads` TBB threads in chunks of 4096 rays and returns the hit count.
#include <embree3/rtcore.h>

#include <cstdint>
#include <vector>

#include "bench/ray/scenes.h"
#include "renderer/core/accel.h"

namespace vesper::bench {

uint64_t raw_intersect1(RTCScene scene, const std::vector<RayRec>& rays, int threads);
uint64_t raw_occluded1(RTCScene scene, const std::vector<RayRec>& rays, int threads);
// Packets of 16 consecutive rays with the coherent flag: an upper bound.
uint64_t raw_intersect16(RTCScene scene, const std::vector<RayRec>& rays, int threads);
uint64_t accel_intersect(const Accel& accel, const std::vector<RayRec>& rays, int threads);

}  // namespace vesper::bench
