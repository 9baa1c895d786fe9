// Deterministic checks of the BSDFs: sample/eval/pdf consistency,
// reciprocity, energy (white and glossy furnaces) and finiteness on
// degenerate inputs. The sampling densities themselves are tested by
// bsdf_chi2_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "renderer/bsdf/bsdf.h"
#include "renderer/math/constants.h"
#include "renderer/sampling/sampler.h"
#include "renderer/sampling/warp.h"

namespace vesper {
namespace {

struct Named {
  std::string name;
  Bsdf bsdf;
};

const Rgb kGoldEta(0.143f, 0.374f, 1.442f), kGoldK(3.983f, 2.385f, 1.603f);
// |eta + i k|^2 >> 1: reflectance 1 - O(1e-8) at every angle.
const Rgb kPerfectEta(1.f), kPerfectK(1e4f);

std::vector<Named> rough_bsdfs() {
  return {
      {"diffuse", DiffuseBsdf{Rgb(0.8f, 0.5f, 0.2f)}},
      {"conductor_a0.01", ConductorBsdf{0.01f, kGoldEta, kGoldK}},
      {"conductor_a0.3", ConductorBsdf{0.3f, kGoldEta, kGoldK}},
      {"conductor_a1", ConductorBsdf{1.f, kGoldEta, kGoldK}},
      {"dielectric_a0.01", DielectricBsdf{1.5f, 0.01f}},
      {"dielectric_a0.2", DielectricBsdf{1.5f, 0.2f}},
      {"dielectric_a0.7_eta1.33", DielectricBsdf{1.33f, 0.7f}},
      {"dielectric_a1_eta0.7", DielectricBsdf{0.7f, 1.f}},
      {"principled_smooth", PrincipledBsdf{Rgb(0.6f, 0.5f, 0.4f), 0.3f, 0.f}},
      {"principled_m0_a0.1", PrincipledBsdf{Rgb(0.8f, 0.3f, 0.2f), 0.f, 0.1f}},
      {"principled_m0.5_a0.5", PrincipledBsdf{Rgb(0.2f, 0.5f, 0.9f), 0.5f, 0.5f}},
      {"principled_m1_a1", PrincipledBsdf{Rgb(0.9f, 0.8f, 0.5f), 1.f, 1.f}},
  };
}

bool close(float a, float b, float rel) {
  return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + 1e-30f;
}
bool close(const Rgb& a, const Rgb& b, float rel) {
  return close(a.r, b.r, rel) && close(a.g, b.g, rel) && close(a.b, b.b, rel);
}

Vec3 direction(float cos_theta, float phi) {
  const float s = safe_sqrt(1.f - cos_theta * cos_theta);
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

// Largest relative change of eval and pdf when wi moves by 1e-5 along an axis.
float sensitivity(const Bsdf& b, const Vec3& wo, const Vec3& wi) {
  const float f = bsdf_eval(b, wo, wi).average(), pdf = bsdf_pdf(b, wo, wi);
  float worst = 0;
  for (int axis = 0; axis < 3; ++axis) {
    for (float step : {-1e-5f, 1e-5f}) {
      Vec3 w = wi;
      w[axis] += step;
      w = normalize(w);
      const float f2 = bsdf_eval(b, wo, w).average(), pdf2 = bsdf_pdf(b, wo, w);
      worst = std::max({worst, std::abs(f2 - f) / std::max(f, 1e-30f),
                        std::abs(pdf2 - pdf) / std::max(pdf, 1e-30f)});
    }
  }
  return worst;
}

// (1) What bsdf_sample returns is what bsdf_eval / bsdf_pdf say at its wi.
TEST(Bsdf, SampleAgreesWithEvalAndPdf) {
  for (const Named& n : rough_bsdfs()) {
    Sampler rng(std::hash<std::string>{}(n.name));
    int checked = 0, mismatched = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec3 wo = sample_uniform_sphere(rng.next2());
      const float uc = rng.next1();
      const auto s = bsdf_sample(n.bsdf, wo, uc, rng.next2());
      if (!s) continue;
      if (s->is_specular) {
        // Zero eval/pdf for the delta lobe; only the principled one has a second lobe.
        if (bsdf_is_delta(n.bsdf)) {
          EXPECT_EQ(bsdf_pdf(n.bsdf, wo, s->wi), 0.f) << n.name;
        }
        continue;
      }
      ++checked;
      const Rgb f = bsdf_eval(n.bsdf, wo, s->wi);
      const float pdf = bsdf_pdf(n.bsdf, wo, s->wi);
      // 1e-4, plus what moving wi by 1e-5 (some 100 float roundings) does to
      // eval: near grazing the rebuilt half vector cancels catastrophically
      // and near the critical angle F has a square-root singularity. A formula
      // error would still show as an O(1) difference.
      const float rel = 1e-4f + sensitivity(n.bsdf, wo, s->wi);
      if (!close(f, s->f, rel) || !close(pdf, s->pdf, rel)) {
        if (++mismatched <= 3)
          ADD_FAILURE() << n.name << " wo " << wo.x << "," << wo.y << "," << wo.z << " wi "
                        << s->wi.x << "," << s->wi.y << "," << s->wi.z << ": sample f " << s->f.r
                        << " pdf " << s->pdf << " vs eval " << f.r << " pdf " << pdf;
      }
      EXPECT_EQ(s->is_transmission, s->wi.z * wo.z < 0.f) << n.name;
    }
    EXPECT_GT(checked, 10000) << n.name;
    EXPECT_EQ(mismatched, 0) << n.name << " of " << checked;
  }
}

// (2) Reflection is reciprocal: f(wo, wi) = f(wi, wo).
TEST(Bsdf, OpaqueBsdfsAreReciprocal) {
  for (const Named& n : rough_bsdfs()) {
    if (std::holds_alternative<DielectricBsdf>(n.bsdf)) continue;  // 1/eta^2 breaks symmetry
    Sampler rng(11);
    int nonzero = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec3 wo = sample_uniform_sphere(rng.next2());
      Vec3 wi = sample_uniform_sphere(rng.next2());
      if (i % 2) wi.z = std::copysign(wi.z, wo.z);  // mostly reflection pairs
      const Rgb a = bsdf_eval(n.bsdf, wo, wi), b = bsdf_eval(n.bsdf, wi, wo);
      nonzero += !a.is_black();
      ASSERT_TRUE(close(a, b, 1e-4f)) << n.name << " " << a.r << " vs " << b.r;
    }
    EXPECT_GT(nonzero, 5000) << n.name;
  }
}

struct Estimate {
  double mean = 0, std_error = 0;
};

// Directional albedo: E[f |cos_i| / pdf] over bsdf_sample (absorbed samples
// count 0), per channel averaged. With `importance`, transmitted weights are
// multiplied back by etap^2 so that reflection + transmission of a lossless
// dielectric sums to 1.
Estimate directional_albedo(const Bsdf& bsdf, const Vec3& wo, int n, uint64_t seed,
                            bool importance = false) {
  Sampler rng(seed);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const float uc = rng.next1();
    const auto s = bsdf_sample(bsdf, wo, uc, rng.next2());
    double w = 0;
    if (s) {
      w = s->f.average() * std::abs(s->wi.z) / s->pdf;
      if (importance && s->is_transmission) {
        const float eta = std::get<DielectricBsdf>(bsdf).eta;
        w *= sqr(wo.z > 0.f ? eta : 1.f / eta);
      }
    }
    sum += w;
    sum2 += w * w;
  }
  const double mean = sum / n, var = std::max(0.0, sum2 / n - mean * mean);
  return {mean, std::sqrt(var / n)};
}

// (3) White furnace: no BSDF creates energy; the lossless ones keep all of it.
TEST(Bsdf, WhiteFurnace) {
  const std::vector<Named> bsdfs = {
      {"diffuse", DiffuseBsdf{Rgb(1.f)}},
      {"conductor_smooth", ConductorBsdf{0.f, kPerfectEta, kPerfectK}},
      {"conductor_a0.2", ConductorBsdf{0.2f, kPerfectEta, kPerfectK}},
      {"conductor_a1", ConductorBsdf{1.f, kPerfectEta, kPerfectK}},
      {"dielectric_smooth", DielectricBsdf{1.5f, 0.f}},
      {"dielectric_a0.1", DielectricBsdf{1.5f, 0.1f}},
      {"dielectric_a0.6", DielectricBsdf{1.5f, 0.6f}},
      {"principled_m0_a0.1", PrincipledBsdf{Rgb(1.f), 0.f, 0.1f}},
      {"principled_m0_a1", PrincipledBsdf{Rgb(1.f), 0.f, 1.f}},
      {"principled_m0_smooth", PrincipledBsdf{Rgb(1.f), 0.f, 0.f}},
      {"principled_m1_a0.3", PrincipledBsdf{Rgb(1.f), 1.f, 0.3f}},
  };
  std::printf("White furnace, directional albedo at cos_o = 0.95, 0.5, 0.15, 0.03, -0.5:\n");
  for (const Named& n : bsdfs) {
    const bool dielectric = std::holds_alternative<DielectricBsdf>(n.bsdf);
    std::printf("  %-22s", n.name.c_str());
    for (float cos_o : {0.95f, 0.5f, 0.15f, 0.03f, -0.5f}) {
      const Vec3 wo = direction(cos_o, 0.3f);
      const Estimate e = directional_albedo(n.bsdf, wo, 200000, 5, dielectric);
      std::printf("  %.4f +- %.4f", e.mean, e.std_error);
      // 1e-5 covers float rounding where the estimate has no variance.
      const double tol = 3 * e.std_error + 1e-5;
      // Known limitation (principled.h): Disney's diffuse and specular lobes
      // are added without coupling, so a white principled surface reflects a
      // little more than it receives at grazing angles (measured ~1.065 at
      // cos_o = 0.03, roughness 1). Bounded there, not hidden.
      const bool uncoupled = std::holds_alternative<PrincipledBsdf>(n.bsdf) && cos_o < 0.1f;
      EXPECT_LE(e.mean, (uncoupled ? 1.1 : 1.0) + tol) << n.name << " cos_o " << cos_o;
      const bool lossless =
          n.name == "diffuse" || n.name == "dielectric_smooth" || n.name == "conductor_smooth";
      if (lossless) {
        EXPECT_NEAR(e.mean, 1.0, tol) << n.name << " cos_o " << cos_o;
      }
    }
    std::printf("\n");
  }
}

// (4) Glossy furnace: a perfect-Fresnel GGX conductor loses energy as it gets
// rougher, because single scattering drops the light that would bounce again
// between microfacets. Documented, not compensated.
TEST(Bsdf, GlossyFurnaceDocumentsGgxEnergyLoss) {
  const float roughness[] = {0.f, 0.25f, 0.5f, 0.75f, 1.f};
  std::printf("GGX conductor (F = 1) directional albedo, single scattering:\n");
  std::printf("  cos_o   r=0      r=0.25   r=0.5    r=0.75   r=1\n");
  for (float cos_o : {0.9f, 0.5f, 0.15f}) {
    const Vec3 wo = direction(cos_o, 1.1f);
    std::printf("  %.2f ", cos_o);
    Estimate prev;
    for (int i = 0; i < 5; ++i) {
      const Bsdf b = ConductorBsdf{sqr(roughness[i]), kPerfectEta, kPerfectK};
      const Estimate e = directional_albedo(b, wo, 300000, 17 + i);
      std::printf("  %.4f", e.mean);
      if (i == 0) {
        EXPECT_NEAR(e.mean, 1.0, 3 * e.std_error + 1e-5);
      } else {
        const double sigma = std::hypot(e.std_error, prev.std_error);
        EXPECT_LE(e.mean, prev.mean + 3 * sigma) << "roughness " << roughness[i];
      }
      if (i == 4) {
        EXPECT_LT(e.mean, 1.0 - 0.05) << "expected a clear loss at roughness 1";
      }
      prev = e;
    }
    std::printf("\n");
  }
}

// (5) Nothing returns NaN, Inf or negative values, whatever the input.
TEST(Bsdf, FiniteOnDegenerateInputs) {
  std::vector<Bsdf> bsdfs;
  for (float a : {0.f, 1e-4f, kSpecularAlpha, 1.0001e-3f, 0.3f, 1.f}) {
    bsdfs.push_back(ConductorBsdf{a, kGoldEta, kGoldK});
    bsdfs.push_back(ConductorBsdf{a, kPerfectEta, kPerfectK});
    bsdfs.push_back(ConductorBsdf{a, Rgb(1.f), Rgb(0.f)});  // eta 1: invisible interface
    for (float eta : {1.5f, 1.f / 1.5f, 1.f, 1.0001f, 3.f}) bsdfs.push_back(DielectricBsdf{eta, a});
    for (float m : {0.f, 0.5f, 1.f}) {
      bsdfs.push_back(PrincipledBsdf{Rgb(1.f), m, a});
      bsdfs.push_back(PrincipledBsdf{Rgb(0.f), m, a});
    }
  }
  bsdfs.push_back(DiffuseBsdf{Rgb(1.f)});

  std::vector<Vec3> dirs = {{0, 0, 1},
                            {0, 0, -1},
                            {1, 0, 0},
                            {0, -1, 0},
                            {0.6f, 0.8f, 0.f},
                            normalize(Vec3(1, 0, 1e-7f)),
                            normalize(Vec3(1, 0, -1e-7f)),
                            normalize(Vec3(1, 1e-6f, 1e-3f))};
  Sampler rng(3);
  for (int i = 0; i < 24; ++i) dirs.push_back(sample_uniform_sphere(rng.next2()));
  const float us[] = {0.f, 1e-7f, 0.5f, kOneMinusEpsilon};

  auto ok = [](const Rgb& f) { return f.is_finite() && f.r >= 0 && f.g >= 0 && f.b >= 0; };
  int64_t samples = 0;
  for (const Bsdf& b : bsdfs) {
    ASSERT_TRUE(ok(bsdf_albedo(b)));
    for (const Vec3& wo : dirs) {
      // wi: every direction, plus wo itself, its mirror and its opposite.
      std::vector<Vec3> wis = dirs;
      wis.push_back(wo);
      wis.push_back(-wo);
      wis.push_back(Vec3(-wo.x, -wo.y, wo.z));
      for (const Vec3& wi : wis) {
        const Rgb f = bsdf_eval(b, wo, wi);
        const float pdf = bsdf_pdf(b, wo, wi);
        ASSERT_TRUE(ok(f)) << b.index() << " f " << f.r;
        ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0) << b.index() << " pdf " << pdf;
      }
      for (float uc : us)
        for (float u0 : us)
          for (float u1 : us) {
            const auto s = bsdf_sample(b, wo, uc, Vec2{u0, u1});
            if (!s) continue;
            ++samples;
            ASSERT_TRUE(ok(s->f)) << b.index() << " sampled f " << s->f.r;
            ASSERT_TRUE(std::isfinite(s->pdf) && s->pdf > 0) << b.index() << " pdf " << s->pdf;
            ASSERT_TRUE(is_finite(s->wi) && std::abs(length(s->wi) - 1.f) < 1e-3f)
                << b.index() << " wi " << s->wi.x << "," << s->wi.y << "," << s->wi.z;
          }
    }
  }
  EXPECT_GT(samples, 10000);
}

}  // namespace
}  // namespace vesper
