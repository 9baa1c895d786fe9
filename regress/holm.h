#pragma once
// Holm's step-down procedure (Holm 1979): which of m hypotheses to reject so
// that the chance of rejecting any true one (the family-wise error rate) is
// at most alpha, whatever their dependence. Used over a layer's tiles: a
// nightly run must raise no false alarm, so the family-wise rate is what
// matters, not a false-discovery rate (Benjamini-Hochberg would accept a
// fixed fraction of false alarms among the flagged tiles). Holm rejects
// everything Bonferroni does and more, at the same guarantee.
#include <span>
#include <vector>

namespace vesper::regress {

// rejected[i] for p_values[i]: sorted ascending, p_(k) (k = 0..m-1) is
// rejected while p_(j) <= alpha / (m - j) for every j <= k.
std::vector<bool> holm_rejections(std::span<const double> p_values, double alpha);

}  // namespace vesper::regress
