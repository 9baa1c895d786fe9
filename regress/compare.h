#pragma once
// Noise-aware comparison of a new frame with its golden: a difference counts
// only when Monte Carlo noise cannot explain it (docs/regression.md).
#include <string>
#include <vector>

#include "regress/regress_result.h"
#include "regress/suite.h"
#include "renderer/output/layered_image.h"

namespace vesper::regress {

// Compares every layer of `golden` and `fresh` (or only `layers` when given:
// "beauty" and EXR layer names) and fills a SceneResult's layers, channel
// differences, verdict and reasons (not its timing or paths: the runner's).
SceneResult compare_frames(const LayeredImage& golden, const LayeredImage& fresh,
                           const std::vector<std::string>* layers, const Thresholds& thresholds);

}  // namespace vesper::regress
