// The photon map (photon_map.h) finds exactly the photons within its
// radius, and photon merging's kernel (photon_merging.h) is normalised: over
// photons of a known density it estimates that density without bias.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "renderer/integrator/photon_map.h"
#include "renderer/integrator/photon_merging.h"
#include "renderer/math/constants.h"

namespace vesper::test {
namespace {

std::vector<Photon> random_photons(size_t n, std::mt19937& rng, float spread) {
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<Photon> photons(n);
  for (size_t i = 0; i < n; ++i) {
    // Clustered and spread at once: a grid sized for neither.
    const float s = i % 3 == 0 ? spread : 0.05f * spread;
    photons[i].p = Vec3(s * u(rng), s * u(rng), s * u(rng));
    photons[i].weight = Rgb(float(i + 1));
    photons[i].light = uint32_t(i);
  }
  return photons;
}

TEST(PhotonMap, FindsExactlyThePhotonsWithinItsRadius) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.2f, 1.2f);
  for (const float radius : {0.01f, 0.05f, 0.3f, 2.f}) {
    SCOPED_TRACE(radius);
    const std::vector<Photon> photons = random_photons(3000, rng, 1.f);
    const PhotonMap map(photons, radius);
    ASSERT_EQ(map.size(), photons.size());
    for (int q = 0; q < 300; ++q) {
      // Query points inside and outside the photons' bounds.
      const Vec3 x(u(rng), u(rng), u(rng));
      std::vector<uint32_t> expected, found;
      for (const Photon& p : photons)
        if (length_squared(p.p - x) <= radius * radius) expected.push_back(p.light);
      map.for_each_near(x, [&](const Photon& p) { found.push_back(p.light); });
      std::sort(found.begin(), found.end());
      ASSERT_EQ(found, expected) << "query " << q;
    }
  }
}

TEST(PhotonMap, EmptyMapFindsNothing) {
  const PhotonMap map({}, 0.1f);
  int n = 0;
  map.for_each_near(Vec3(0.f), [&](const Photon&) { ++n; });
  EXPECT_EQ(n, 0);
  EXPECT_THROW(PhotonMap({}, 0.f), std::invalid_argument);
}

// The estimates' mean is `truth` (two-sided Z-test, alpha = 0.01: |z| <
// 2.576), and their standard error is below 3 % of it, so that a kernel
// volume or area off by 10 % would be caught.
void expect_mean_is(const std::vector<double>& estimates, double truth) {
  double mean = 0, var = 0;
  for (double e : estimates) mean += e / double(estimates.size());
  for (double e : estimates) var += (e - mean) * (e - mean) / double(estimates.size() - 1);
  const double se = std::sqrt(var / double(estimates.size()));
  EXPECT_LT(std::abs(mean - truth) / se, 2.576) << "mean " << mean << " against " << truth;
  EXPECT_LT(se, 0.03 * truth);
}

// m photons of weight w from n subpaths, uniform over the unit cube (dims
// 3, medium photons) or the unit square z = 0 (dims 2, surface photons):
// the kernel's estimate at a random point away from the faces, from 60
// independent maps.
std::vector<double> kernel_estimates(int dims, size_t m, uint64_t n, float w, float radius,
                                     uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<double> estimates;
  for (int trial = 0; trial < 60; ++trial) {
    std::vector<Photon> photons(m);
    for (Photon& p : photons) {
      p.p = Vec3(u(rng), u(rng), dims == 3 ? u(rng) : 0.f);
      p.n = dims == 3 ? Vec3(0.f) : Vec3(0, 0, 1);
      p.weight = Rgb(w);
    }
    PhotonMerging pm;
    (dims == 3 ? pm.map : pm.surface_map) = PhotonMap(std::move(photons), radius);
    pm.subpaths = n;
    const Vec3 x(0.3f + 0.4f * u(rng), 0.5f, dims == 3 ? 0.5f : 0.f);
    double sum = 0;
    (dims == 3 ? pm.map : pm.surface_map).for_each_near(x, [&](const Photon& p) {
      sum += p.weight.r;
    });
    estimates.push_back(sum * (dims == 3 ? pm.scale() : pm.surface_scale()));
  }
  return estimates;
}

TEST(PhotonMerging, KernelEstimatesAUniformDensityWithoutBias) {
  // sum_p weight_p * scale() estimates the weight per unit volume over N,
  // M w / N.
  expect_mean_is(kernel_estimates(3, 20000, 5000, 0.5f, 0.08f, 11), 20000 * 0.5 / 5000);
}

TEST(PhotonMerging, SurfaceKernelEstimatesAUniformDensityWithoutBias) {
  // ... and surface_scale() per unit area.
  expect_mean_is(kernel_estimates(2, 4000, 1000, 0.25f, 0.06f, 13), 4000 * 0.25 / 1000);
}

TEST(PhotonMerging, RadiusShrinksAsThePhotonsGrow) {
  // k = 32 photons in the ball at a million photons' mean density, and r
  // falling as photons^-0.2 (consistency: bias and variance both vanish).
  const double volume = 8.0;
  const float r = photon_radius(1e6, volume);
  EXPECT_NEAR(4.0 / 3.0 * kPi * r * r * r * 1e6 / volume, 32.0, 1e-3 * 32.0);
  EXPECT_NEAR(photon_radius(32e6, volume) / r, std::pow(32.0, -0.2), 1e-4);
  EXPECT_EQ(photon_radius(0, volume), 0.f);
}

}  // namespace
}  // namespace vesper::test
