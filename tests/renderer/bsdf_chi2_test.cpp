// Chi-square goodness of fit of every non-delta BSDF's sampling routine
// against its bsdf_pdf, over the whole sphere, including the probability of
// returning no sample. alpha = 0.01 for the whole file, Sidak-corrected.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "renderer/bsdf/bsdf.h"
#include "renderer/sampling/sampler.h"
#include "tests/renderer/chi2.h"

namespace vesper {
namespace {

struct Chi2Case {
  std::string name;
  Bsdf bsdf;
  float cos_o = 1;     // |cos theta| of wo
  bool below = false;  // wo.z < 0 (inside a dielectric)
};

// Keeps gtest's failure lines readable.
void PrintTo(const Chi2Case& c, std::ostream* os) { *os << c.name; }

const Rgb kGoldEta(0.143f, 0.374f, 1.442f), kGoldK(3.983f, 2.385f, 1.603f);

std::vector<Chi2Case> make_cases() {
  struct Base {
    std::string name;
    Bsdf bsdf;
    bool below;
  };
  const auto alpha = [](float roughness) { return roughness * roughness; };
  std::vector<Base> bases = {
      {"diffuse", DiffuseBsdf{Rgb(0.7f, 0.5f, 0.3f)}, false},
      {"conductor_r0.2", ConductorBsdf{alpha(0.2f), kGoldEta, kGoldK}, false},
      {"conductor_r0.5", ConductorBsdf{alpha(0.5f), kGoldEta, kGoldK}, false},
      {"conductor_r1", ConductorBsdf{alpha(1.f), kGoldEta, kGoldK}, false},
      {"principled_m0_r0.3", PrincipledBsdf{Rgb(0.8f, 0.5f, 0.3f), 0.f, alpha(0.3f)}, false},
      {"principled_m0.5_r0.6", PrincipledBsdf{Rgb(0.3f, 0.6f, 0.9f), 0.5f, alpha(0.6f)}, false},
      {"principled_m1_r0.2", PrincipledBsdf{Rgb(0.9f, 0.7f, 0.4f), 1.f, alpha(0.2f)}, false},
  };
  for (float r : {0.3f, 0.7f}) {
    for (bool below : {false, true}) {
      const std::string side = below ? "_inside" : "_outside";
      bases.push_back({"dielectric_r" + std::to_string(r).substr(0, 3) + side,
                       DielectricBsdf{1.5f, alpha(r)}, below});
    }
  }
  std::vector<Chi2Case> cases;
  for (const Base& b : bases) {
    for (float c : {0.9f, 0.5f, 0.15f})
      cases.push_back({b.name + "_cos" + std::to_string(c).substr(0, 4), b.bsdf, c, b.below});
  }
  return cases;
}

const std::vector<Chi2Case>& all_cases() {
  static const std::vector<Chi2Case> cases = make_cases();
  return cases;
}

class BsdfChi2 : public ::testing::TestWithParam<Chi2Case> {};

TEST_P(BsdfChi2, SamplingMatchesPdf) {
  const Chi2Case& c = GetParam();
  // An azimuth off the grid's phi = 0 seam.
  const float sin_o = std::sqrt(1.f - c.cos_o * c.cos_o), phi_o = 0.7f;
  const Vec3 wo(sin_o * std::cos(phi_o), sin_o * std::sin(phi_o), c.below ? -c.cos_o : c.cos_o);
  ASSERT_FALSE(bsdf_is_delta(c.bsdf));

  Sampler rng(std::hash<std::string>{}(c.name));
  int64_t specular = 0;
  auto sample = [&]() -> std::optional<Vec3> {
    const float uc = rng.next1();
    const auto s = bsdf_sample(c.bsdf, wo, uc, rng.next2());
    if (!s) return std::nullopt;
    specular += s->is_specular;
    return s->wi;
  };
  auto pdf = [&](const Vec3& wi) { return double(bsdf_pdf(c.bsdf, wo, wi)); };

  stats::Chi2Options options;
  options.theta_bins = 20;
  options.phi_bins = 40;
  options.attempts = 1'000'000;
  const stats::Chi2Result r = stats::chi2_test(sample, pdf, options);
  EXPECT_EQ(specular, 0);
  const double level = stats::sidak_alpha(0.01, int(all_cases().size()));
  EXPECT_GT(r.p_value, level) << r.message;
  std::printf("%-40s p = %.4f  (chi2 %.1f, dof %d, sampled %.4f)\n", c.name.c_str(), r.p_value,
              r.statistic, r.dof, r.sampled_fraction);
}

// The test must be able to fail: a slightly wrong roughness in the pdf, and a
// sampler that silently drops 1% of its samples, are both rejected.
TEST(BsdfChi2Control, RejectsMismatchedPdfAndMissingMass) {
  const Bsdf sampled = ConductorBsdf{0.25f, kGoldEta, kGoldK};
  const Bsdf claimed = ConductorBsdf{0.25f * 1.05f, kGoldEta, kGoldK};
  const Vec3 wo(0.6f, 0.f, 0.8f);
  Sampler rng(7);
  int64_t i = 0;
  auto sample = [&](bool drop) -> std::optional<Vec3> {
    const float uc = rng.next1();
    const auto s = bsdf_sample(sampled, wo, uc, rng.next2());
    if (!s || (drop && ++i % 100 == 0)) return std::nullopt;
    return s->wi;
  };
  stats::Chi2Options options;
  options.theta_bins = 20;
  options.phi_bins = 40;
  options.attempts = 300'000;
  const auto wrong_pdf =
      stats::chi2_test([&] { return sample(false); },
                       [&](const Vec3& w) { return bsdf_pdf(claimed, wo, w); }, options);
  EXPECT_LT(wrong_pdf.p_value, 1e-6) << wrong_pdf.message;
  const auto dropped =
      stats::chi2_test([&] { return sample(true); },
                       [&](const Vec3& w) { return bsdf_pdf(sampled, wo, w); }, options);
  EXPECT_LT(dropped.p_value, 1e-6) << dropped.message;
}

std::string case_name(const ::testing::TestParamInfo<Chi2Case>& info) {
  std::string s = info.param.name;
  for (char& ch : s)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(AllBsdfs, BsdfChi2, ::testing::ValuesIn(all_cases()), case_name);

}  // namespace
}  // namespace vesper
