#include "worker/render_progress.h"

#include <gtest/gtest.h>

namespace vesper::worker_detail {
namespace {

TEST(RenderProgress, TakesTheLastPlainProgressLine) {
  EXPECT_EQ(last_render_progress(""), std::nullopt);
  EXPECT_EQ(last_render_progress("[info] scene.json: 64x48, 16 spp\n"), std::nullopt);
  EXPECT_DOUBLE_EQ(*last_render_progress("render:   0% (elapsed 0.0s, eta 0.0s)\n"
                                         "render:  40% (elapsed 1.2s, eta 1.8s)\n"),
                   0.4);
  EXPECT_DOUBLE_EQ(*last_render_progress("render: 100% (elapsed 3s, eta 0s)\n[info] wrote x\n"),
                   1.0);
  // A truncated last line falls back to the one before.
  EXPECT_DOUBLE_EQ(*last_render_progress("render:  30% (e\nrender:  4"), 0.3);
}

}  // namespace
}  // namespace vesper::worker_detail
