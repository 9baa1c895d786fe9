#pragma once
// Motion blur by instance: when every step of a moving primitive is an affine
// image of its first step (what keyed corners, centres, radii and mesh
// transforms give), Embree traces the first step's static BVH through one
// motion transform per step. Embree interpolates those matrices linearly, and
// a linear blend of affine maps moves every point along the same straight
// line as blending the vertices, so the surface at any time is the one vertex
// time steps give. vesper_motion_bench measured instances faster to trace and
// to build than vertex time steps (bench/README.md); a deforming mesh (keyed
// positions) keeps vertex time steps.
#include <array>
#include <optional>
#include <vector>

#include "renderer/core/accel_geometry.h"

namespace vesper {

// An affine map as Embree's RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR: the three
// columns of the linear part, then the translation.
using MotionTransform = std::array<float, 12>;

// The map from step 0 to each step (the first is the identity), or nullopt
// when the steps are not affine images of step 0 (or a map is singular).
// Primitives without steps give nullopt.
std::optional<std::vector<MotionTransform>> rigid_motion(const AccelQuad& q);
std::optional<std::vector<MotionTransform>> rigid_motion(const AccelSphere& s);
std::optional<std::vector<MotionTransform>> rigid_motion(const AccelMesh& m);

}  // namespace vesper
