// Procedural cloud. The noise is hand-written (3D gradient noise in the style
// of Perlin's improved noise, with hashed gradients; ~40 lines): Debian has no
// noise library package worth a dependency for this.
#include "renderer/volume/cloud.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace vesper {
namespace {

std::uint32_t hash3(int x, int y, int z, std::uint32_t seed) {
  // A few rounds of integer mixing (lowbias32 by C. Wellons) over the lattice point.
  std::uint32_t h = seed * 0x9E3779B9u;
  for (std::uint32_t v : {std::uint32_t(x), std::uint32_t(y), std::uint32_t(z)}) {
    h ^= v + 0x7F4A7C15u + (h << 6) + (h >> 2);
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    h *= 0x846CA68Bu;
    h ^= h >> 16;
  }
  return h;
}

// One of the 12 cube-edge gradients (improved noise), dotted with (x,y,z).
float grad(std::uint32_t h, float x, float y, float z) {
  switch (h % 12u) {
    case 0:
      return x + y;
    case 1:
      return -x + y;
    case 2:
      return x - y;
    case 3:
      return -x - y;
    case 4:
      return x + z;
    case 5:
      return -x + z;
    case 6:
      return x - z;
    case 7:
      return -x - z;
    case 8:
      return y + z;
    case 9:
      return -y + z;
    case 10:
      return y - z;
    default:
      return -y - z;
  }
}

float fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }
float lerp(float a, float b, float t) { return a + (b - a) * t; }

// splitmix64: small, well-mixed, fully specified (std distributions are not
// portable across standard libraries, this is).
struct SplitMix {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
};

struct Sphere {
  float x, y, z, r;
};

// How the cloud has changed after `time` frames (CloudParams::time): smooth
// in time, and exactly the still cloud at 0 (cos 1, sin 0, drift 0, growth 1).
struct Evolution {
  float cos_turn = 1, sin_turn = 0;  // the noise domain's turn about +y
  float drift = 0;                   // the noise domain's shift along +x, cloud half-widths
  float growth = 1;                  // the puffs' radius factor
};

Evolution evolution(double time) {
  if (!std::isfinite(time)) throw std::invalid_argument("cloud time must be finite");
  Evolution e;
  if (time == 0) return e;
  const double turn = 0.015 * time;  // radians per frame
  e.cos_turn = float(std::cos(turn));
  e.sin_turn = float(std::sin(turn));
  e.drift = float(0.02 * time);
  e.growth = float(1.0 + 0.2 * std::tanh(time / 48.0));
  return e;
}

}  // namespace

float smooth_min(float a, float b, float k) {
  if (k <= 0.0f) return std::min(a, b);
  const float h = std::max(k - std::abs(a - b), 0.0f) / k;
  return std::min(a, b) - h * h * k * 0.25f;
}

float gradient_noise(float x, float y, float z, std::uint32_t seed) {
  const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const int ix = int(fx), iy = int(fy), iz = int(fz);
  const float u = x - fx, v = y - fy, w = z - fz;
  const float a = fade(u), b = fade(v), c = fade(w);
  auto g = [&](int dx, int dy, int dz) {
    return grad(hash3(ix + dx, iy + dy, iz + dz, seed), u - float(dx), v - float(dy),
                w - float(dz));
  };
  const float x00 = lerp(g(0, 0, 0), g(1, 0, 0), a), x10 = lerp(g(0, 1, 0), g(1, 1, 0), a);
  const float x01 = lerp(g(0, 0, 1), g(1, 0, 1), a), x11 = lerp(g(0, 1, 1), g(1, 1, 1), a);
  return lerp(lerp(x00, x10, b), lerp(x01, x11, b), c);
}

float fbm(float x, float y, float z, int octaves, std::uint32_t seed) {
  float sum = 0, amp = 0.5f, norm = 0;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * gradient_noise(x, y, z, seed + std::uint32_t(o) * 101u);
    norm += amp;
    x = x * 2.03f + 17.1f;  // lacunarity ~2, offset to decorrelate octaves
    y = y * 2.03f + 5.3f;
    z = z * 2.03f + 11.7f;
    amp *= 0.5f;
  }
  return norm > 0 ? sum / norm : 0.0f;
}

DenseVolume generate_cloud(const CloudParams& p) {
  if (p.resolution < 8 || p.resolution > 1024)
    throw std::invalid_argument("cloud resolution must be in [8, 1024], got " +
                                std::to_string(p.resolution));
  if (!(p.voxel_size > 0) || !std::isfinite(p.voxel_size))
    throw std::invalid_argument("cloud voxel size must be positive");
  if (p.noise_octaves < 0 || p.noise_octaves > 12)
    throw std::invalid_argument("cloud noise octaves must be in [0, 12]");
  if (!(p.noise_amplitude >= 0 && p.noise_amplitude <= 0.3f))
    throw std::invalid_argument("cloud noise amplitude must be in [0, 0.3]");
  if (p.spheres < 1 || p.spheres > 64)
    throw std::invalid_argument("cloud sphere count must be in [1, 64]");
  if (!(p.density_band > 0)) throw std::invalid_argument("cloud density band must be positive");

  // Normalised cloud space: x, z in [-1, 1] across the volume, y in [-0.25, 0.75]
  // (the volume is half as tall as it is wide), the flat base at y = -0.12.
  SplitMix rng{p.seed ^ 0xC10D5EEDull};
  // A big central puff and smaller ones around it, higher towards the middle.
  std::vector<Sphere> spheres{{0.0f, 0.1f, 0.0f, 0.3f}};
  for (int s = 1; s < p.spheres; ++s) {
    const double ang = rng.uniform(0, 2 * M_PI), rad = 0.5 * std::sqrt(rng.uniform());
    const float r =
        float(rng.uniform(0.12, 0.24)) * float(1.0 - 0.6 * rad);  // smaller puffs further out
    spheres.push_back({float(rad * std::cos(ang)) * 1.2f,
                       float(rng.uniform(-0.05, 0.2)) + 0.15f * float(0.5 - rad),
                       float(rad * std::sin(ang)) * 0.9f, r + 0.06f});
  }
  const float base_y = -0.12f;
  const std::uint32_t noise_seed = std::uint32_t(rng.next());
  const Evolution evo = evolution(p.time);
  for (Sphere& s : spheres) s.r *= evo.growth;

  DenseVolume vol;
  vol.nx = vol.nz = p.resolution;
  vol.ny = p.resolution / 2;
  vol.voxel_size = p.voxel_size;
  // Centred on x = z = 0 in world space, bottom of the volume at y = 0.
  vol.origin = Vec3d(-0.5 * (vol.nx - 1) * p.voxel_size, 0.0, -0.5 * (vol.nz - 1) * p.voxel_size);
  vol.values.assign(size_t(vol.nx) * vol.ny * vol.nz, 0.0f);
  const float h = 2.0f / float(p.resolution);  // normalised units per voxel

  tbb::parallel_for(0, vol.nz, [&](int k) {
    const float z = (float(k) - 0.5f * float(vol.nz - 1)) * h;
    for (int j = 0; j < vol.ny; ++j) {
      const float y = -0.25f + (float(j) + 0.5f) * h;
      for (int i = 0; i < vol.nx; ++i) {
        const float x = (float(i) - 0.5f * float(vol.nx - 1)) * h;
        float d = 1e9f;
        for (const Sphere& s : spheres) {
          const float dx = x - s.x, dy = y - s.y, dz = z - s.z;
          d = smooth_min(d, std::sqrt(dx * dx + dy * dy + dz * dz) - s.r, p.smoothness);
        }
        d = -smooth_min(-d, y - base_y,
                        0.05f);  // smooth max with the half-space y > base_y: flat bottom
        if (d > 1.5f * p.noise_amplitude + p.density_band)
          continue;  // far outside: |fbm| <~ 1.05 cannot reach
        // Displacement is weaker at the flat base (cumulus bottoms are smooth).
        const float base_fade = std::clamp((y - base_y) / 0.15f, 0.25f, 1.0f);
        const float nx = evo.cos_turn * x - evo.sin_turn * z + evo.drift;
        const float nz = evo.sin_turn * x + evo.cos_turn * z;
        d += p.noise_amplitude * base_fade *
             fbm(nx * p.noise_frequency, y * p.noise_frequency, nz * p.noise_frequency,
                 p.noise_octaves, noise_seed);
        // Fog volume: 0 outside, smooth ramp to 1 over the band inside the surface.
        const float t = std::clamp(-d / p.density_band, 0.0f, 1.0f);
        vol.values[(size_t(k) * vol.ny + j) * vol.nx + i] = t * t * (3.0f - 2.0f * t);
      }
    }
  });
  return vol;
}

}  // namespace vesper
