// Participating media: transmittance, volume furnace, grid vs homogeneous,
// majorant grid vs global majorant, Henyey-Greenstein sampling, stress.
#include <gtest/gtest.h>

#include <filesystem>

#include "chi2.h"
#include "render_stats.h"
#include "renderer/integrator/volume_tracking.h"
#include "renderer/media/henyey_greenstein.h"
#include "renderer/volume/vdb_io.h"
#include "scene_fixtures.h"
#include "test_grids.h"
#include "tests/common/temp_dir.h"

namespace vesper::test {
namespace {

constexpr double kAlpha = 0.01;

// A grid medium of constant density 1 filling the world box [lo, hi] exactly
// (n voxels per side).
VdbMediumDesc constant_grid_box(Rgb sa, Rgb ss, double g, Vec3d lo, double size, int n = 9) {
  VdbMediumDesc v;
  v.file = "test-grid";
  v.density =
      std::make_shared<FunctionGrid>(n, size / (n - 1), lo, [](const Vec3&) { return 1.f; });
  v.sigma_a = sa;
  v.sigma_s = ss;
  v.g = g;
  return v;
}

// ---- transmittance ---------------------------------------------------------

TEST(Transmittance, HomogeneousSlabIsExactlyBeerLambert) {
  SceneDescription d = empty_scene(4, 4, 1, 1);
  add_medium(d, "fog",
             fog_box(Rgb(0.2f, 0.5f, 1.f), Rgb(0.3f, 0.1f, 0.f), 0, {-10, -10, -1}, {10, 10, 1}));
  const Scene scene = build_scene(d);
  Sampler s(uint64_t(1));
  const Vec3d o_world{0.5, 0.3, -5}, dir = normalize(Vec3d(0.1, 0.2, 1));
  const Ray ray{Vec3((o_world - scene.origin) / scene.unit_scale), Vec3(dir)};
  const Rgb tr = estimate_transmittance(scene.media, ray, 1e30f, s);
  const double path = 2.0 / dir.z;  // through the slab z in [-1, 1]
  const double expect[3] = {std::exp(-0.5 * path), std::exp(-0.6 * path), std::exp(-1.0 * path)};
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(tr[c], expect[c], 1e-5 * expect[c] + 1e-7) << "channel " << c;
}

TEST(Transmittance, RatioTrackingThroughConstantGridMatchesBeerLambert) {
  // Ratio tracking is a random estimator: its mean over many rays must match
  // exp(-sigma_t d) (Z-test, alpha = 0.01).
  SceneDescription d = empty_scene(4, 4, 1, 1);
  add_medium(d, "grid", constant_grid_box(Rgb(0.3f), Rgb(0.4f, 0.2f, 0.1f), 0, {-1, -1, -1}, 2.0));
  const Scene scene = build_scene(d);
  const Vec3d o_world{0.2, -0.1, -4};
  const Ray ray{Vec3((o_world - scene.origin) / scene.unit_scale), Vec3(0, 0, 1)};
  const int n = 200000;
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    Sampler s(uint64_t(77), uint64_t(i), 0);
    const Rgb tr = estimate_transmittance(scene.media, ray, 1e30f, s);
    for (int c = 0; c < 3; ++c) {
      sum[c] += tr[c];
      sum2[c] += double(tr[c]) * tr[c];
    }
  }
  const double sigma_t[3] = {0.7, 0.5, 0.4};
  const double z = sidak_z_critical(kAlpha, 3);
  for (int c = 0; c < 3; ++c) {
    const double mean = sum[c] / n, var = sum2[c] / n - mean * mean;
    const double expect = std::exp(-sigma_t[c] * 2.0);
    EXPECT_LT(std::abs(mean - expect) / std::sqrt(var / n), z)
        << "channel " << c << " mean " << mean << " expected " << expect;
  }
}

TEST(Transmittance, RatioTrackingThroughConstantVdbFileMatchesBeerLambert) {
  // A real .vdb written and read back through OpenVDB/NanoVDB: density 1 on
  // voxels 0..n-1 (voxel size h); trilinear blending with the zero background
  // adds a one-voxel ramp at each face, i.e. half a voxel of optical length
  // per face, so the optical depth along an axis is sigma_t * (n - 1 + 1) * h.
  const int n = 12;
  const double h = 0.1;
  DenseVolume vol;
  vol.nx = vol.ny = vol.nz = n;
  vol.values.assign(size_t(n * n * n), 1.f);
  vol.voxel_size = h;
  vol.origin = {0, 0, 0};
  const TempDir dir("tr");
  write_vdb_fog_volume(vol, "density", dir / "c.vdb");
  VdbMediumDesc v;
  v.file = (dir / "c.vdb").string();
  v.density = load_vdb_grid(dir / "c.vdb", "density");
  v.sigma_a = Rgb(0.5f);
  v.sigma_s = Rgb(1.0f);
  SceneDescription d = empty_scene(4, 4, 1, 1);
  d.camera.from = {0.55, 0.55, -3};
  d.camera.to = {0.55, 0.55, 0};
  add_medium(d, "vdb", v);
  const Scene scene = build_scene(d);
  const Ray ray{Vec3(0.f), Vec3(0, 0, 1)};  // render space starts at the camera
  const int samples = 100000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < samples; ++i) {
    Sampler s(uint64_t(3), uint64_t(i), 0);
    const double t = estimate_transmittance(scene.media, ray, 1e30f, s).r;
    sum += t;
    sum2 += t * t;
  }
  const double mean = sum / samples, se = std::sqrt((sum2 / samples - mean * mean) / samples);
  const double expect = std::exp(-1.5 * n * h);
  EXPECT_LT(std::abs(mean - expect) / se, sidak_z_critical(kAlpha, 1))
      << "mean " << mean << " expected " << expect;
}

// ---- furnace ---------------------------------------------------------------

void expect_volume_furnace(double g) {
  SceneDescription d = empty_scene(24, 24, 16, 1000);
  d.camera.from = {0, 0, 4};
  d.camera.to = {0, 0, 0};
  d.camera.fov_degrees = 30;
  add_light(d, EnvironmentLightDesc{});
  add_medium(d, "cloud", fog_box(Rgb(0.f), Rgb(1.5f), g, {-0.8, -0.8, -0.8}, {0.8, 0.8, 0.8}));
  const Scene scene = build_scene(d);
  const TileStats st = tile_stats(scene, 12, 16, 6);
  const double crit = sidak_t_critical(kAlpha, int(st.mean.size()), st.batches - 1);
  for (size_t t = 0; t < st.mean.size(); ++t)
    EXPECT_LT(std::abs(st.mean[t] - 1.0) / std::max(st.se[t], 1e-7), crit)
        << "g=" << g << " tile " << t << " mean " << st.mean[t] << " se " << st.se[t];
}

TEST(VolumeFurnace, BackScatteringMediumVanishes) { expect_volume_furnace(-0.5); }
TEST(VolumeFurnace, IsotropicMediumVanishes) { expect_volume_furnace(0.0); }
TEST(VolumeFurnace, ForwardScatteringMediumVanishes) { expect_volume_furnace(0.8); }

// ---- grid vs homogeneous ----------------------------------------------------

SceneDescription lit_box_scene() {
  SceneDescription d = empty_scene(24, 24, 16, 8);
  d.camera.from = {0, 0.2, 3.5};
  d.camera.to = {0, 0, 0};
  d.camera.fov_degrees = 35;
  const uint32_t floor = add_material(d, "floor", DiffuseMaterialDesc{Rgb(0.5f)});
  add_quad(d, {-3, -1, 3}, {6, 0, 0}, {0, 0, -6}, floor);
  add_light(d, PointLightDesc{{0.5, 2.0, 0.5}, Rgb(6.f)});
  add_light(d, EnvironmentLightDesc{Rgb(0.2f), std::nullopt, "", 1, 0});
  return d;
}

void expect_same_tiles(const Scene& a, const Scene& b, int batches = 10) {
  const TileStats sa = tile_stats(a, batches, 16, 6, 100);
  const TileStats sb = tile_stats(b, batches, 16, 6, 900);
  const double crit = sidak_t_critical(kAlpha, int(sa.mean.size()), batches - 1);
  for (size_t t = 0; t < sa.mean.size(); ++t) {
    const double se = std::sqrt(sa.se[t] * sa.se[t] + sb.se[t] * sb.se[t]);
    EXPECT_LT(std::abs(sa.mean[t] - sb.mean[t]) / std::max(se, 1e-9), crit)
        << "tile " << t << ": " << sa.mean[t] << " vs " << sb.mean[t];
  }
}

TEST(GridMedium, ConstantDensityGridRendersLikeHomogeneousMedium) {
  SceneDescription a = lit_box_scene(), b = lit_box_scene();
  const Rgb sa(0.2f), ss(1.2f, 1.0f, 0.8f);
  add_medium(a, "fog", fog_box(sa, ss, 0.3, {-0.7, -0.7, -0.7}, {0.7, 0.7, 0.7}));
  add_medium(b, "grid", constant_grid_box(sa, ss, 0.3, {-0.7, -0.7, -0.7}, 1.4));
  expect_same_tiles(build_scene(a), build_scene(b));
}

TEST(GridMedium, MajorantGridAndGlobalMajorantAgree) {
  SceneDescription d = lit_box_scene();
  VdbMediumDesc v;
  v.file = "blob";
  const int n = 33;
  v.density =
      std::make_shared<FunctionGrid>(n, 1.6 / (n - 1), Vec3d(-0.8, -0.8, -0.8), [n](const Vec3& p) {
        const Vec3 c = p / float(n - 1) - Vec3(0.5f);
        return std::max(0.f, 1.f - 4.f * length_squared(c)) * (1.f + 0.5f * std::sin(12.f * c.x));
      });
  v.sigma_s = Rgb(3.f);
  v.sigma_a = Rgb(0.5f);
  add_medium(d, "blob", v);
  SceneBuildOptions global;
  global.media.majorant_grid = false;
  SceneBuildOptions fine;
  fine.media.majorant_cell_voxels = 4;
  expect_same_tiles(build_scene(d, fine), build_scene(d, global));
}

// ---- emission ------------------------------------------------------------------

TEST(GridEmission, GlowingSlabMatchesTheEmissionAbsorptionIntegral) {
  // Camera looks straight through a glowing, absorbing cube of side 2 (no
  // lights): L = eps / sigma_a * (1 - exp(-sigma_a * 2)) on every pixel that
  // sees the cube through its front and back faces.
  const double sigma_a = 0.8, eps = 1.5;
  SceneDescription d = empty_scene(16, 16, 16, 4);
  d.camera.from = {0, 0, 10};
  d.camera.to = {0, 0, 0};
  d.camera.fov_degrees = 4;  // nearly parallel rays: path length 2 within 0.1%
  VdbMediumDesc v = constant_grid_box(Rgb(float(sigma_a)), Rgb(0.f), 0, {-1, -1, -1}, 2.0);
  v.emission = std::make_shared<FunctionGrid>(
      9, 2.0 / 8, Vec3d(-1, -1, -1), [](const Vec3&) { return 1.f; }, "temperature");
  v.emission_grid = "temperature";
  v.emission_scale = eps;
  v.emission_color = Rgb(1.f, 0.5f, 0.25f);
  add_medium(d, "glow", v);
  const Scene scene = build_scene(d);
  const TileStats st = tile_stats(scene, 12, 16, 4);
  const double path = 2.0 / std::cos(2.0 * M_PI / 180.0 * std::sqrt(2.0));  // longest corner ray
  const double lum = 0.2126 + 0.7152 * 0.5 + 0.0722 * 0.25;
  const double lo = lum * eps / sigma_a * (1 - std::exp(-sigma_a * 2.0));
  const double hi = lum * eps / sigma_a * (1 - std::exp(-sigma_a * path));
  const double crit = sidak_t_critical(kAlpha, int(st.mean.size()), st.batches - 1);
  for (size_t t = 0; t < st.mean.size(); ++t) {
    const double se = std::max(st.se[t], 1e-9);
    const double dev =
        st.mean[t] < lo ? lo - st.mean[t] : (st.mean[t] > hi ? st.mean[t] - hi : 0.0);
    EXPECT_LT(dev / se, crit) << "tile " << t << " mean " << st.mean[t] << " expected in [" << lo
                              << ", " << hi << "]";
  }
}

// Emission only (sigma_t = 0), or with a thin absorber, is integrated on its
// own (integrator/volume_emission.h): a camera looking straight through a
// glowing cube of side 2 sees L = eps * 2 without absorption and
// eps / sigma_a * (1 - exp(-2 sigma_a)) with it, per channel.
struct GlowCube {
  double eps = 1.5;
  Rgb grid_sigma_a;  // of the glowing grid itself
  Rgb fog_sigma_a;   // of a homogeneous box around the same cube
  Rgb color{1.f, 0.5f, 0.25f};
  Scene build() const {
    SceneDescription d = empty_scene(16, 16, 16, 4);
    d.camera.from = {0, 0, 10};
    d.camera.to = {0, 0, 0};
    d.camera.fov_degrees = 4;  // nearly parallel rays: path length 2 within 0.1%
    VdbMediumDesc v = constant_grid_box(grid_sigma_a, Rgb(0.f), 0, {-1, -1, -1}, 2.0);
    if (grid_sigma_a.is_black()) v.density_scale = 0;
    v.emission = std::make_shared<FunctionGrid>(
        9, 2.0 / 8, Vec3d(-1, -1, -1), [](const Vec3&) { return 1.f; }, "temperature");
    v.emission_grid = "temperature";
    v.emission_scale = eps;
    v.emission_color = color;
    add_medium(d, "glow", v);
    if (!fog_sigma_a.is_black())
      add_medium(d, "fog", fog_box(fog_sigma_a, Rgb(0.f), 0, {-1, -1, -1}, {1, 1, 1}));
    return build_scene(d);
  }
  // Luminance of the analytic radiance along a path of length `path`.
  double expected(double path) const {
    const Rgb sa = grid_sigma_a + fog_sigma_a;
    const double w[3] = {0.2126, 0.7152, 0.0722};
    double lum = 0;
    for (int c = 0; c < 3; ++c) {
      const double s = sa[c];
      const double integral = s > 0 ? (1 - std::exp(-s * path)) / s : path;
      lum += w[c] * color[c] * eps * integral;
    }
    return lum;
  }
};

// Z-test (alpha = kAlpha, Sidak over tiles) of every tile against the
// analytic range over the pixels' path lengths; returns the largest relative
// standard error of a tile mean, the estimator's noise.
double expect_glow_matches_analytic(const GlowCube& cube) {
  const TileStats st = tile_stats(cube.build(), 12, 16, 4);
  const double longest = 2.0 / std::cos(2.0 * M_PI / 180.0 * std::sqrt(2.0));  // corner ray
  const double a = cube.expected(2.0), b = cube.expected(longest);
  const double lo = std::min(a, b), hi = std::max(a, b);
  const double crit = sidak_t_critical(kAlpha, int(st.mean.size()), st.batches - 1);
  double worst_rel_se = 0;
  for (size_t t = 0; t < st.mean.size(); ++t) {
    // Float rounding: a deterministic estimate may sit a hair outside [lo, hi].
    const double se = std::max(st.se[t], 1e-6 * hi);
    const double dev =
        st.mean[t] < lo ? lo - st.mean[t] : (st.mean[t] > hi ? st.mean[t] - hi : 0.0);
    EXPECT_LT(dev / se, crit) << "tile " << t << " mean " << st.mean[t] << " expected in [" << lo
                              << ", " << hi << "]";
    worst_rel_se = std::max(worst_rel_se, st.se[t] / st.mean[t]);
  }
  return worst_rel_se;
}

TEST(GridEmission, EmissionOnlyGridGivesTheLineIntegral) {
  // sigma_a = sigma_s = 0: delta tracking meets no collision at all; the
  // emission must still be there (it rendered black before).
  GlowCube cube;
  const double rel_se = expect_glow_matches_analytic(cube);
  std::printf("emission only: worst tile relative standard error %.2e\n", rel_se);
}

TEST(GridEmission, ThinAbsorberKeepsTheNoiseOfNoAbsorber) {
  // sigma_a = 0.01: about 0.02 real collisions per ray. The collision
  // estimator (emission / sigma_maj at each) had a per-sample relative
  // standard deviation of ~1/sqrt(0.02) = 7 here (tile relative SE ~0.4);
  // the track-length estimator stays as quiet as without absorption.
  GlowCube none;
  GlowCube thin;
  thin.grid_sigma_a = Rgb(0.01f);
  const double se_none = expect_glow_matches_analytic(none);
  const double se_thin = expect_glow_matches_analytic(thin);
  std::printf("relative SE: sigma_a = 0 %.2e, sigma_a = 0.01 %.2e\n", se_none, se_thin);
  EXPECT_LT(se_thin, 5e-3);  // ~80x below the collision estimator
}

TEST(GridEmission, ChromaticHomogeneousFogAttenuatesGridEmission) {
  // An emission-only grid inside a chromatic absorbing homogeneous box:
  // delta tracking's null collisions change the throughput per channel along
  // the segment, and the emission integral must follow each step.
  GlowCube cube;
  cube.fog_sigma_a = Rgb(0.3f, 0.8f, 1.6f);
  cube.color = Rgb(1.f);
  expect_glow_matches_analytic(cube);
}

// ---- phase function sampling ---------------------------------------------------

class HgChi2 : public ::testing::TestWithParam<float> {};

TEST_P(HgChi2, SamplingMatchesPdf) {
  const HgPhase phase{GetParam()};
  const Vec3 wo = normalize(Vec3(0.3f, -0.4f, 0.8f));
  Sampler s(uint64_t(31));
  stats::Chi2Options opt;
  opt.pole = -wo;
  opt.theta_bins = 30;
  const auto r =
      stats::chi2_test([&]() -> std::optional<Vec3> { return phase.sample(wo, s.next2()); },
                       [&](const Vec3& wi) -> double { return phase.pdf(wo, wi); }, opt);
  EXPECT_GT(r.p_value, stats::sidak_alpha(kAlpha, 5)) << r.message;
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-3);
}
INSTANTIATE_TEST_SUITE_P(SeveralG, HgChi2, ::testing::Values(-0.7f, -0.2f, 0.f, 0.5f, 0.9f));

TEST(HgPhase, MeanCosineIsG) {
  // E[cos(-wo, wi)] = g for Henyey-Greenstein.
  for (float g : {-0.6f, 0.f, 0.3f, 0.85f}) {
    const HgPhase phase{g};
    const Vec3 wo(0, 0, 1);
    Sampler s(uint64_t(5));
    double sum = 0, sum2 = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const double c = dot(-wo, phase.sample(wo, s.next2()));
      sum += c;
      sum2 += c * c;
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_LT(std::abs(mean - g) / se, sidak_z_critical(kAlpha, 4)) << "g=" << g;
  }
}

// ---- stress --------------------------------------------------------------------

bool finite_image(const RenderResult& r) {
  for (float v : r.image.pixels)
    if (!std::isfinite(v)) return false;
  return r.stats.nonfinite_samples == 0;
}

TEST(VolumeStress, DensityScalesFrom1e3To1e4StayFinite) {
  for (double scale : {1e-3, 1.0, 1e2, 1e4}) {
    SceneDescription d = lit_box_scene();
    VdbMediumDesc v = constant_grid_box(Rgb(0.1f), Rgb(1.f), 0.5, {-0.7, -0.7, -0.7}, 1.4);
    v.density_scale = scale;
    add_medium(d, "grid", v);
    RenderOptions o;
    o.spp = 4;
    EXPECT_TRUE(finite_image(render(build_scene(d), o))) << "density_scale " << scale;
  }
}

TEST(VolumeStress, PurelyAbsorbingCameraInsideAndFarAwayMediaStayFinite) {
  // sigma_s = 0, unbounded fog around the camera, and the whole scene 1e5 away.
  SceneDescription d = lit_box_scene();
  add_medium(d, "absorb", fog_box(Rgb(0.5f), Rgb(0.f), 0, {-0.7, -0.7, -0.7}, {0.7, 0.7, 0.7}));
  HomogeneousMediumDesc everywhere;
  everywhere.sigma_s = Rgb(0.05f);
  add_medium(d, "air", everywhere);
  RenderOptions o;
  o.spp = 4;
  EXPECT_TRUE(finite_image(render(build_scene(d), o)));

  SceneDescription far = lit_box_scene();
  const Vec3d off{1e5, 2e5, -1e5};
  far.camera.from = far.camera.from + off;
  far.camera.to = far.camera.to + off;
  for (auto& s : far.shapes) std::get<QuadShapeDesc>(s.geometry).corner += off;
  std::get<PointLightDesc>(far.lights[0].light).position += off;
  add_medium(far, "fog", fog_box(Rgb(0.1f), Rgb(1.f), 0.2, off - Vec3d(0.7), off + Vec3d(0.7)));
  add_medium(far, "grid", constant_grid_box(Rgb(0.1f), Rgb(1.f), 0.0, off - Vec3d(0.5), 1.0));
  const RenderResult r = render(build_scene(far), o);
  EXPECT_TRUE(finite_image(r));
  double sum = 0;
  for (float v : r.image.pixels) sum += v;
  EXPECT_GT(sum, 0.0);
}

}  // namespace
}  // namespace vesper::test
