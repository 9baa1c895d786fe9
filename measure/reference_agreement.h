#pragma once
// Do two renderers' references show the same picture? A mistranslated scene
// (a light twice as bright, a missing medium, a wrong material) shows as a
// ratio of image means away from 1, or as 16x16 blocks whose mean ratio is.
// Each reference converges to its own renderer's answer, so some spread is
// expected (noise, filters, light-transport differences); the bands below
// flag what noise and small model differences do not explain.
#include <string>
#include <vector>

#include "renderer/output/layered_image.h"

namespace vesper::measure {

struct AgreementBands {
  double mean_ratio_lo = 0.95, mean_ratio_hi = 1.0 / 0.95;  // whole image
  double block_ratio_lo = 0.8, block_ratio_hi = 1.0 / 0.8;  // 5th and 95th percentiles
  int block_size = 16;                                      // pixels a side
  // Blocks darker than this (mean of RGB, in both images) are left out:
  // their ratio is noise over nothing.
  double min_block_mean = 1e-3;
};

struct ReferenceAgreement {
  double mean_ratio = 0;  // mean(a) / mean(b), over pixels and R, G, B
  int blocks = 0;         // blocks compared (not too dark)
  double block_min = 0, block_p05 = 0, block_p95 = 0, block_max = 0;
  bool flagged = false;
  std::vector<std::string>
      reasons;  // why flagged, e.g. "image mean ratio 1.31 outside [0.95, 1.05]"
};

// `a` and `b` need R, G, B and the same size (std::invalid_argument
// otherwise). Partial blocks at the right and bottom edges count.
ReferenceAgreement compare_references(const LayeredImage& a, const LayeredImage& b,
                                      const AgreementBands& bands = {});

}  // namespace vesper::measure
