#pragma once
// Where a ray's time falls between motion steps, the way Embree interpolates
// (rtcSetGeometryTimeStepCount with the default time range [0, 1]): K steps,
// step k at time k / (K - 1), linear in between. Used to rebuild a moving
// primitive's hit point and normal at the ray's time, and for the camera.
#include <algorithm>
#include <cstddef>

#include "renderer/math/vec.h"

namespace vesper {

struct StepPosition {
  size_t step = 0;  // the segment [step, step + 1]
  float f = 0;      // fraction of the way to step + 1
};

inline StepPosition step_position(size_t steps, float time) {
  const float t = std::clamp(time, 0.f, 1.f) * float(steps - 1);
  const size_t k = std::min(size_t(t), steps - 2);
  return {k, t - float(k)};
}

template <typename T>
T lerp_steps(const T& a, const T& b, float f) {
  return a * (1.f - f) + b * f;
}

}  // namespace vesper
