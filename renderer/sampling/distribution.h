#pragma once
// Piecewise-constant 1D and 2D distributions for importance sampling tabulated
// functions (environment maps, light selection).
#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

#include "renderer/math/constants.h"
#include "renderer/math/vec.h"

namespace vesper {

class Distribution1D {
 public:
  Distribution1D() = default;
  // Negative or non-finite weights are treated as zero; all-zero falls back to uniform.
  explicit Distribution1D(std::vector<float> weights) : func_(std::move(weights)) {
    const size_t n = func_.size();
    cdf_.assign(n + 1, 0.0);
    for (auto& w : func_) w = (w > 0.f && std::isfinite(w)) ? w : 0.f;
    for (size_t i = 0; i < n; ++i) cdf_[i + 1] = cdf_[i] + double(func_[i]);
    total_ = cdf_[n];
    if (!(total_ > 0.0)) {
      std::fill(func_.begin(), func_.end(), 1.f);
      for (size_t i = 0; i < n; ++i) cdf_[i + 1] = double(i + 1);
      total_ = double(n);
    }
    for (auto& c : cdf_) c /= total_;
  }

  size_t size() const { return func_.size(); }
  // Integral of the step function over [0, 1].
  double integral() const { return total_ / double(func_.size()); }
  // Probability of picking bin i in sample_discrete.
  float discrete_pmf(size_t i) const { return float(cdf_[i + 1] - cdf_[i]); }
  // Density on [0, 1] at bin i.
  float pdf(size_t i) const { return discrete_pmf(i) * float(func_.size()); }

  size_t sample_discrete(float u, float* pmf = nullptr, float* u_remapped = nullptr) const {
    const size_t i = find_bin(u);
    const double p = cdf_[i + 1] - cdf_[i];
    if (pmf) *pmf = float(p);
    if (u_remapped) *u_remapped = std::min(float((u - cdf_[i]) / p), kOneMinusEpsilon);
    return i;
  }
  // Continuous sample in [0, 1) with density pdf(bin).
  float sample_continuous(float u, float* pdf_out, size_t* bin = nullptr) const {
    const size_t i = find_bin(u);
    const double p = cdf_[i + 1] - cdf_[i];
    const double du = (double(u) - cdf_[i]) / p;
    if (pdf_out) *pdf_out = float(p * double(func_.size()));
    if (bin) *bin = i;
    return std::min(float((double(i) + du) / double(func_.size())), kOneMinusEpsilon);
  }

 private:
  size_t find_bin(float u) const {
    // Last index with cdf <= u, skipping zero-probability bins.
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), double(u));
    size_t i = size_t(std::max<std::ptrdiff_t>(0, (it - cdf_.begin()) - 1));
    i = std::min(i, func_.size() - 1);
    while (i > 0 && cdf_[i + 1] - cdf_[i] <= 0.0) --i;
    while (i + 1 < func_.size() && cdf_[i + 1] - cdf_[i] <= 0.0) ++i;
    return i;
  }

  std::vector<float> func_;
  std::vector<double> cdf_;
  double total_ = 0;
};

// f(u, v) on [0,1]^2 given as rows (v) of columns (u).
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(const std::vector<float>& values, int width, int height) {
    std::vector<float> row_weights(static_cast<size_t>(height));
    rows_.reserve(size_t(height));
    for (int y = 0; y < height; ++y) {
      std::vector<float> row(values.begin() + ptrdiff_t(y) * width,
                             values.begin() + ptrdiff_t(y + 1) * width);
      const double sum = std::accumulate(row.begin(), row.end(), 0.0,
                                         [](double a, float b) { return a + std::max(0.f, b); });
      row_weights[size_t(y)] = float(sum);
      rows_.emplace_back(std::move(row));
    }
    marginal_ = Distribution1D(std::move(row_weights));
  }

  Vec2 sample(Vec2 u, float* pdf) const {
    float pdf_v = 0, pdf_u = 0;
    size_t row = 0;
    const float v = marginal_.sample_continuous(u.y, &pdf_v, &row);
    const float uu = rows_[row].sample_continuous(u.x, &pdf_u);
    *pdf = pdf_u * pdf_v;
    return {uu, v};
  }
  float pdf(Vec2 uv) const {
    const size_t h = marginal_.size();
    const size_t row = std::min(size_t(uv.y * float(h)), h - 1);
    const size_t w = rows_[row].size();
    const size_t col = std::min(size_t(uv.x * float(w)), w - 1);
    return marginal_.pdf(row) * rows_[row].pdf(col);
  }

 private:
  std::vector<Distribution1D> rows_;
  Distribution1D marginal_;
};

}  // namespace vesper
