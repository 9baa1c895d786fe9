#include "bench/sampling/allocation_bound.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "renderer/output/film_sums.h"

namespace vesper::bench {
namespace {

// Per pixel and sample: relMSE's term a and the stopping metric's term b.
struct PixelTerms {
  std::vector<double> relmse, stopping;
};

PixelTerms pixel_terms(const LayeredImage& ref, int ref_spp) {
  const char* beauty[3] = {"R", "G", "B"};
  PixelTerms t;
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) {
      double a = 0, b = 0;
      for (int c = 0; c < 3; ++c) {
        const double m = ref.at(x, y, size_t(ref.channel_index(beauty[c])));
        const double var =
            ref.at(x, y, size_t(ref.channel_index(kVarianceChannels[size_t(c)]))) * ref_spp;
        a += var / (m * m + 0.01) / 3;
        b = std::max(b, var / std::pow(std::abs(m) + 0.01, 2));
      }
      t.relmse.push_back(a);
      t.stopping.push_back(b);
    }
  return t;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / double(v.size());
}

// The mean spp of the allocation n_i = max(min_spp, weight_i / level) whose
// relMSE (mean of a_i / n_i) is `relmse`, found by bisection on log(level).
double spp_at_relmse(const std::vector<double>& a, const std::vector<double>& weight,
                     double min_spp, double relmse) {
  const auto allocate = [&](double level, double& spp) {
    double err = 0;
    spp = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      const double n = std::max(min_spp, weight[i] / level);
      err += a[i] / n;
      spp += n;
    }
    spp /= double(a.size());
    return err / double(a.size());
  };
  double lo = -60, hi = 60, spp = 0;  // log(level): relMSE grows with it
  for (int i = 0; i < 200; ++i) {
    const double mid = (lo + hi) / 2;
    (allocate(std::exp(mid), spp) > relmse ? hi : lo) = mid;
  }
  allocate(std::exp(lo), spp);
  return spp;
}

}  // namespace

AllocationBounds allocation_bounds(const LayeredImage& reference, int reference_spp,
                                   int uniform_spp, int min_spp) {
  const PixelTerms t = pixel_terms(reference, reference_spp);
  const double relmse = mean(t.relmse) / uniform_spp, m = min_spp;
  std::vector<double> root(t.relmse.size());
  std::transform(t.relmse.begin(), t.relmse.end(), root.begin(),
                 [](double a) { return std::sqrt(a); });
  AllocationBounds b;
  b.threshold_max_channel = uniform_spp / spp_at_relmse(t.relmse, t.stopping, m, relmse);
  b.threshold_relmse = uniform_spp / spp_at_relmse(t.relmse, t.relmse, m, relmse);
  b.neyman = uniform_spp / spp_at_relmse(t.relmse, root, m, relmse);
  return b;
}

}  // namespace vesper::bench
