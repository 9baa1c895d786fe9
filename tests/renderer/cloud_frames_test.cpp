// The evolving cloud of `vesper vdb cloud --frames` (CloudParams::time):
// deterministic, smooth between frames, and different over a shot.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/volume/cloud.h"

namespace vesper {
namespace {

DenseVolume cloud_at(double time) {
  CloudParams p;
  p.resolution = 32;
  p.voxel_size = 0.08;
  p.time = time;
  return generate_cloud(p);
}

// Mean absolute voxel difference relative to the mean density of `a`.
double relative_l1(const DenseVolume& a, const DenseVolume& b) {
  double diff = 0, mass = 0;
  for (size_t i = 0; i < a.values.size(); ++i) {
    diff += std::abs(double(a.values[i]) - double(b.values[i]));
    mass += a.values[i];
  }
  return diff / mass;
}

double mass(const DenseVolume& v) {
  double m = 0;
  for (const float x : v.values) m += x;
  return m;
}

TEST(CloudFrames, TimeZeroIsTheStillCloudAndAFrameIsDeterministic) {
  CloudParams still;
  still.resolution = 32;
  still.voxel_size = 0.08;
  EXPECT_EQ(cloud_at(0).values, generate_cloud(still).values);
  EXPECT_EQ(cloud_at(7).values, cloud_at(7).values);
}

TEST(CloudFrames, NeighbouringFramesAreCloseAndAShotApartDiffers) {
  const DenseVolume f0 = cloud_at(0), f1 = cloud_at(1), f11 = cloud_at(11), f12 = cloud_at(12),
                    f23 = cloud_at(23);
  const double step = std::max(relative_l1(f0, f1), relative_l1(f11, f12));
  const double shot = relative_l1(f0, f23);
  EXPECT_GT(step, 0);  // it moves every frame
  EXPECT_LT(step, 0.1);
  EXPECT_GT(shot, 5 * step);  // and drifts far over a shot
  // It grows: more density at the end of the shot.
  EXPECT_GT(mass(f23), 1.1 * mass(f0));
}

TEST(CloudFrames, ANonFiniteTimeIsRefused) {
  CloudParams p;
  p.time = std::nan("");
  EXPECT_THROW(generate_cloud(p), std::invalid_argument);
}

}  // namespace
}  // namespace vesper
