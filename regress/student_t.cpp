#include "regress/student_t.h"

#include <cmath>
#include <stdexcept>

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace vesper::regress {
namespace {

// Beyond this the t and the normal tails agree to ~1e-7 relative at the
// critical values used here; the normal is the exact limit.
constexpr double kNormalDof = 1e7;

}  // namespace

double two_sided_p_value(double t, double dof) {
  if (!(dof > 0)) throw std::invalid_argument("two_sided_p_value: degrees of freedom must be > 0");
  if (std::isnan(t)) return 1;
  if (dof >= kNormalDof) return std::erfc(std::abs(t) / std::sqrt(2.0));
  if (std::isinf(t)) return 0;
  return 2 * boost::math::cdf(boost::math::complement(boost::math::students_t(dof), std::abs(t)));
}

double two_sided_critical_value(double p, double dof) {
  if (!(p > 0 && p <= 1))
    throw std::invalid_argument("two_sided_critical_value: p must be in (0, 1]");
  if (!(dof > 0))
    throw std::invalid_argument("two_sided_critical_value: degrees of freedom must be > 0");
  if (dof >= kNormalDof)
    return boost::math::quantile(boost::math::complement(boost::math::normal(), p / 2));
  return boost::math::quantile(boost::math::complement(boost::math::students_t(dof), p / 2));
}

}  // namespace vesper::regress
