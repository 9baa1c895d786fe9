#include "tests/renderer/chi2.h"

#include <algorithm>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <numeric>
#include <sstream>
#include <vector>

#include "renderer/math/frame.h"

namespace vesper::stats {
namespace {

constexpr double kPiD = 3.14159265358979323846;
double sq(double x) { return x * x; }

// Adaptive Simpson on [a, b] with cached end and mid values; eps is absolute.
template <typename F>
double simpson_step(const F& f, double a, double b, double fa, double fm, double fb, double whole,
                    double eps, int depth) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6 * (fa + 4 * flm + fm);
  const double right = (b - m) / 6 * (fm + 4 * frm + fb);
  const double delta = left + right - whole;
  if (depth <= 0 || std::abs(delta) <= 15 * eps) return left + right + delta / 15;
  return simpson_step(f, a, m, fa, flm, fm, left, 0.5 * eps, depth - 1) +
         simpson_step(f, m, b, fm, frm, fb, right, 0.5 * eps, depth - 1);
}

// Starts from a few panels so that a narrow peak inside [a, b] is not missed.
template <typename F>
double integrate(const F& f, double a, double b, double eps, int depth = 10, int panels = 3) {
  double sum = 0;
  const double h = (b - a) / panels;
  for (int i = 0; i < panels; ++i) {
    const double x0 = a + i * h, x1 = x0 + h, xm = 0.5 * (x0 + x1);
    const double f0 = f(x0), fm = f(xm), f1 = f(x1);
    sum += simpson_step(f, x0, x1, f0, fm, f1, h / 6 * (f0 + 4 * fm + f1), eps / panels, depth);
  }
  return sum;
}

struct Cell {
  double observed = 0, expected = 0;
  int index = 0;  // theta * phi_bins + phi; -1 for "no sample"
};

std::string describe(const Cell& c, const Chi2Options& o) {
  std::ostringstream s;
  if (c.index < 0) {
    s << "no-sample cell";
  } else {
    const int t = c.index / o.phi_bins, p = c.index % o.phi_bins;
    s << "cell theta[" << t * 180.0 / o.theta_bins << "," << (t + 1) * 180.0 / o.theta_bins
      << ") deg phi[" << p * 360.0 / o.phi_bins << "," << (p + 1) * 360.0 / o.phi_bins << ") deg";
  }
  s << ": observed " << c.observed << ", expected " << c.expected;
  return s.str();
}

}  // namespace

double chi2_p_value(double statistic, int dof) {
  return dof > 0 ? boost::math::gamma_q(0.5 * dof, 0.5 * statistic) : 1.0;
}

double sidak_alpha(double alpha, int m) { return 1.0 - std::pow(1.0 - alpha, 1.0 / m); }

Chi2Result chi2_test(const std::function<std::optional<Vec3>()>& sample,
                     const std::function<double(const Vec3&)>& pdf, const Chi2Options& o) {
  const Frame frame = Frame::from_normal(normalize(o.pole));
  const int nt = o.theta_bins, np = o.phi_bins;
  const double n = double(o.attempts);
  std::vector<Cell> cells(size_t(nt * np) + 1);
  for (int i = 0; i < nt * np; ++i) cells[i].index = i;
  Cell& none = cells.back();
  none.index = -1;

  // Observed counts.
  for (int64_t i = 0; i < o.attempts; ++i) {
    const std::optional<Vec3> w = sample();
    if (!w) {
      none.observed += 1;
      continue;
    }
    const Vec3 l = frame.to_local(*w);
    const double theta = std::acos(std::clamp(double(l.z), -1.0, 1.0));
    double phi = std::atan2(double(l.y), double(l.x));
    if (phi < 0) phi += 2 * kPiD;
    const int t = std::min(nt - 1, int(theta / kPiD * nt));
    const int p = std::min(np - 1, int(phi / (2 * kPiD) * np));
    cells[size_t(t * np + p)].observed += 1;
  }

  // Expected counts: n times the integral of pdf * sin(theta) over each cell.
  // The absolute tolerance keeps quadrature error far below one sample.
  const double eps = 1e-2 / n;
  const double dt = kPiD / nt, dp = 2 * kPiD / np;
  double integral = 0;
  for (int t = 0; t < nt; ++t) {
    for (int p = 0; p < np; ++p) {
      auto inner = [&](double theta) {
        const double st = std::sin(theta), ct = std::cos(theta);
        auto f = [&](double phi) {
          const Vec3 l(float(st * std::cos(phi)), float(st * std::sin(phi)), float(ct));
          return pdf(frame.to_world(l));
        };
        return st * integrate(f, p * dp, (p + 1) * dp, eps / dt);
      };
      const double v = integrate(inner, t * dt, (t + 1) * dt, eps);
      cells[size_t(t * np + p)].expected = n * v;
      integral += v;
    }
  }
  none.expected = std::max(0.0, n * (1.0 - integral));

  Chi2Result r;
  r.pdf_integral = integral;
  r.sampled_fraction = 1.0 - none.observed / n;
  std::ostringstream msg;
  if (integral > 1.0 + 1e-3) msg << "pdf integrates to " << integral << " > 1. ";

  // Worst cells first, for the failure message.
  std::vector<Cell> by_error = cells;
  auto err = [](const Cell& c) {
    return c.expected > 0 ? sq(c.observed - c.expected) / c.expected : c.observed;
  };
  std::sort(by_error.begin(), by_error.end(),
            [&](const Cell& a, const Cell& b) { return err(a) > err(b); });

  // Pool the cells expected below min_expected, smallest first (pbrt-v3).
  std::sort(cells.begin(), cells.end(),
            [](const Cell& a, const Cell& b) { return a.expected < b.expected; });
  double pooled_obs = 0, pooled_exp = 0, chi2 = 0;
  int dof = 0;
  for (const Cell& c : cells) {
    if (c.expected == 0) {
      if (c.observed > n * 1e-5) {
        msg << "samples where the pdf is zero: " << describe(c, o) << ". ";
        r.message = msg.str();
        return r;  // p_value = 0
      }
    } else if (c.expected < o.min_expected || (pooled_exp > 0 && pooled_exp < o.min_expected)) {
      pooled_obs += c.observed;
      pooled_exp += c.expected;
    } else {
      chi2 += sq(c.observed - c.expected) / c.expected;
      ++dof;
    }
  }
  if (pooled_exp > 0) {
    chi2 += sq(pooled_obs - pooled_exp) / pooled_exp;
    ++dof;
  }
  dof -= 1;  // the counts sum to the number of attempts
  r.statistic = chi2;
  r.dof = dof;
  r.p_value = chi2_p_value(chi2, dof);
  msg << "chi2 " << chi2 << " dof " << dof << " p " << r.p_value << " pdf integral " << integral
      << " sampled " << r.sampled_fraction << "; worst:";
  for (size_t i = 0; i < std::min<size_t>(4, by_error.size()); ++i)
    msg << "\n  " << describe(by_error[i], o);
  r.message = msg.str();
  return r;
}

}  // namespace vesper::stats
