#pragma once
// A reference is itself a Monte Carlo estimate: rendered as two independent
// halves A and B (different seeds), it is their mean, and the spread between
// the halves says how much error it still carries — the floor below which no
// measured relMSE against it means anything.
#include "renderer/output/layered_image.h"

namespace vesper::measure {

// (A + B) / 2, channel by channel (same size and channels; else
// std::invalid_argument). Metadata: A's.
LayeredImage mean_of_halves(const LayeredImage& a, const LayeredImage& b);

// The reference's own relMSE against the truth, estimated from its halves:
//   A and B are unbiased with the same per-pixel variance s^2 and
//   independent, so E[(A - B)^2] = 2 s^2, while the reference R = (A + B) / 2
//   has E[(R - truth)^2] = s^2 / 2 = E[(A - B)^2] / 4.
// Hence floor = mean over pixels and RGB of (A - B)^2 / (R^2 + 0.01) / 4:
// relMSE(A, B) / 4 with the reference R, not B, in the denominator, exactly
// as measured renders are scored against R (DESIGN.md's relMSE).
double reference_noise_floor(const LayeredImage& a, const LayeredImage& b);

}  // namespace vesper::measure
