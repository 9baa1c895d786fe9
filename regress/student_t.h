#pragma once
// Student's t distribution, two-sided: the p-value of a tile's difference
// when its variance is itself estimated (from a few degrees of freedom per
// pixel), and the critical value a test at level p needs. With infinite
// degrees of freedom both are the standard normal's.
#include <limits>

namespace vesper::regress {

constexpr double kInfiniteDof = std::numeric_limits<double>::infinity();

// P(|T| >= |t|) for T ~ Student's t with `dof` > 0 degrees of freedom.
double two_sided_p_value(double t, double dof);

// The t >= 0 with two_sided_p_value(t, dof) == p, for p in (0, 1].
double two_sided_critical_value(double p, double dof);

}  // namespace vesper::regress
