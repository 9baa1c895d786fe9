#pragma once
// What a sample allocation can gain at best, from the reference's own
// per-pixel variance: the equal-error gain over uniform sampling of an ideal
// allocation (each pixel's variance known exactly, any sample count allowed,
// every sample costing the same). Separates what the allocation rule can
// give from what estimating the variance, passes and per-pixel cost take.
#include "renderer/output/layered_image.h"

namespace vesper::bench {

struct AllocationBounds {
  // Samples until sqrt(var) / (|mean| + 0.01), max over R, G, B, is below a
  // threshold, at least min_spp (the first adaptive rule's metric).
  double threshold_max_channel = 0;
  // The same with relMSE's own per-pixel term (mean over R, G, B of
  // var / (mean² + 0.01)) as the metric.
  double threshold_relmse = 0;
  // Samples in proportion to the per-sample relMSE term's square root
  // (Neyman allocation), at least min_spp: the least relMSE for the samples.
  double neyman = 0;
};

// Gains at the relMSE that uniform sampling reaches with `uniform_spp`.
// `reference` needs R, G, B and variance.R/G/B (the variance of its mean over
// `reference_spp` samples).
AllocationBounds allocation_bounds(const LayeredImage& reference, int reference_spp,
                                   int uniform_spp, int min_spp);

}  // namespace vesper::bench
