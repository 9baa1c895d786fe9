#pragma once
// Pearson chi-square goodness-of-fit test of a direction sampler against the
// density it claims, over the whole sphere (after pbrt-v3's chi2test and
// Mitsuba's ChiSquareTest). Reusable for BSDF, light and environment sampling.
//
// - Directions are binned on a (theta, phi) grid in the frame of `pole`
//   (theta in [0, pi] uniform, phi in [0, 2 pi)).
// - Expected counts are attempts * integral of the pdf over each bin, by
//   nested adaptive Simpson quadrature in double precision.
// - Attempts that return no direction (absorbed samples) go to one extra
//   "no sample" cell whose expectation is attempts * (1 - integral of the pdf
//   over the sphere), so missing or surplus mass is tested too.
// - Cells expected below `min_expected` are pooled (smallest first) into one
//   cell; samples in a cell of zero density fail the test outright.
// - The p-value is the upper regularised incomplete gamma function
//   Q(dof / 2, chi2 / 2) from Boost.Math (header only, Debian's libboost-dev).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "renderer/math/vec.h"

namespace vesper::stats {

struct Chi2Options {
  int theta_bins = 10;
  int phi_bins = 20;
  int64_t attempts = 1'000'000;
  double min_expected = 5;
  Vec3 pole{0.f, 0.f, 1.f};  // the grid's theta = 0 axis
};

struct Chi2Result {
  double p_value = 0;
  double statistic = 0;
  int dof = 0;
  double pdf_integral = 0;      // integral of the pdf over the sphere
  double sampled_fraction = 0;  // attempts that returned a direction
  std::string message;          // what went wrong, and the worst cells
};

// `sample` performs one attempt; `pdf` is a solid-angle density on the sphere.
Chi2Result chi2_test(const std::function<std::optional<Vec3>()>& sample,
                     const std::function<double(const Vec3&)>& pdf,
                     const Chi2Options& options = {});

// P(X >= statistic) for X chi-square distributed with `dof` degrees of freedom.
double chi2_p_value(double statistic, int dof);

// Per-test level so that m independent tests together reject with `alpha` (Sidak).
double sidak_alpha(double alpha, int m);

}  // namespace vesper::stats
