// No false alarms: renders of an unchanged scene with 20 other seeds are
// compared with one golden, every layer, at the default thresholds. Low spp
// is the hard case (heavier-tailed pixels, variance estimates from few
// samples), so these run at 32 spp; the power tests add a high-spp control.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "regress/compare.h"
#include "render_fixtures.h"

namespace vesper::test {
namespace {

using regress::Verdict;

struct Worst {
  double max_abs_z = 0, histogram_distance = 0, histogram_margin = 0;
};

Worst expect_no_false_alarm(const SceneDescription& scene, const char* label, bool layer_variance) {
  const LayeredImage golden = render_with_variance(scene, 1000, layer_variance);
  Worst worst;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const LayeredImage fresh = render_with_variance(scene, seed, layer_variance);
    const regress::SceneResult r = regress::compare_frames(golden, fresh, nullptr, {});
    std::string reasons;
    for (const std::string& s : r.reasons) reasons += "\n  " + s;
    EXPECT_EQ(r.verdict, Verdict::Pass) << label << " seed " << seed << ":" << reasons;
    for (const regress::LayerResult& l : r.layers) {
      EXPECT_EQ(l.has_variance, layer_variance || l.layer == "beauty") << label << " " << l.layer;
      worst.max_abs_z = std::max(worst.max_abs_z, l.max_abs_z);
      worst.histogram_distance = std::max(worst.histogram_distance, l.histogram_distance);
      worst.histogram_margin =
          std::max(worst.histogram_margin, l.histogram_distance / l.histogram_noise);
    }
  }
  std::printf("%s: 20 seeds, max |Z| %.2f, max histogram distance %.4f stops (%.2f of noise)\n",
              label, worst.max_abs_z, worst.histogram_distance, worst.histogram_margin);
  return worst;
}

TEST(NoFalseAlarms, CornellTwentySeeds) {
  // The surfaces layer without variance channels: NaN/Inf and histogram checks.
  const Worst w = expect_no_false_alarm(cornell(64, 64, 32), "cornell 64x64 32 spp", false);
  EXPECT_GT(w.max_abs_z, 0.5);  // the tiles were tested
}

TEST(NoFalseAlarms, FogShaftsTwentySeeds) {
  // Every layer with its variance: the fog layer's tiles are tested too.
  const Worst w = expect_no_false_alarm(fog_shafts(64, 32), "fog-shafts 64x48 32 spp", true);
  EXPECT_GT(w.max_abs_z, 0.5);
}

}  // namespace
}  // namespace vesper::test
