#pragma once
// Procedural cumulus cloud as an OpenVDB-ready fog volume (no OpenVDB here):
// a signed distance field = smooth union of a seeded cluster of spheres,
// flattened at the bottom, displaced by fBm gradient noise, turned into a
// density that is 0 outside and ramps to 1 inside over `density_band`.
#include <cstdint>

#include "renderer/volume/vdb_io.h"

namespace vesper {

struct CloudParams {
  int resolution = 128;  // voxels along x and z; y gets resolution/2
  std::uint64_t seed = 1;
  double voxel_size = 0.02;      // world units; the cloud is resolution*voxel_size wide
  float noise_amplitude = 0.08;  // SDF displacement, in units of the cloud half-width
  int noise_octaves = 5;
  float noise_frequency = 4.0f;  // base fBm frequency, per cloud half-width
  int spheres = 12;              // including the central one
  float smoothness = 0.12f;      // polynomial smooth-min k, in cloud half-widths
  float density_band = 0.06f;    // inside distance over which density rises 0 -> 1
  // Frames since the first (`vesper vdb cloud --frames`: frame - 1). The cloud
  // evolves smoothly: its noise domain drifts along +x and turns about +y,
  // and its puffs grow (towards 1.2x, tanh-shaped). 0 is the still cloud, bitwise.
  double time = 0;
};

// Throws std::invalid_argument for out-of-range parameters. Deterministic:
// the same params give bitwise the same volume on any thread count.
DenseVolume generate_cloud(const CloudParams& params);

// Exposed for tests: polynomial smooth minimum (Quilez), smin(a,b,k) <= min(a,b),
// equal to min(a,b) when |a-b| >= k.
float smooth_min(float a, float b, float k);
// Gradient noise in about [-1,1], 0 at integer lattice points; and its fBm.
float gradient_noise(float x, float y, float z, std::uint32_t seed);
float fbm(float x, float y, float z, int octaves, std::uint32_t seed);

}  // namespace vesper
