#pragma once
// Equiangular sampling on against off, tile by tile (estimator_agreement.h):
// both must render the same expected image; the standard errors say which is
// less noisy.
#include "estimator_agreement.h"

namespace vesper::test {

struct OnOffNoise {
  double se_on = 0, se_off = 0;  // mean tile standard error, equiangular on / off
};

inline OnOffNoise expect_on_and_off_agree(const Scene& scene, int batches = 10, int tile = 6) {
  // Light tracing off: it would take the deep paths, whose equiangular
  // samples these tests are also about.
  RenderOptions on, off;
  on.light_traced_from = off.light_traced_from = 0;
  off.equiangular = false;
  const EstimatorNoise noise = expect_estimators_agree(scene, on, off, batches, tile);
  return {noise.se_a, noise.se_b};
}

}  // namespace vesper::test
