// Render time: judged on the fastest repeat (accidents only slow a render
// down), against the golden's and, when given, the recent median.
#include <gtest/gtest.h>

#include "regress/render_time.h"
#include "regress/verdicts.h"

namespace vesper::regress {
namespace {

SceneResult timed(double golden, std::vector<double> repeats) {
  SceneResult s;
  s.name = "cornell";
  s.golden_seconds = golden;
  s.new_seconds_repeats = std::move(repeats);
  return s;
}

TEST(RenderTime, ASlowdownBeyondTheLimitOnEveryRepeatRegresses) {
  SceneResult s = timed(10, {13, 14, 16});  // 30 % slower at best: the default limit is 1.2
  judge_render_time(s, {});
  EXPECT_EQ(s.verdict, Verdict::Regressed);
  EXPECT_EQ(s.new_seconds, 14);  // the median is what the report shows
  ASSERT_EQ(s.reasons.size(), 1u);
  EXPECT_EQ(
      s.reasons[0],
      "render time 13.00 s (fastest of 3) is 1.30x the golden's 10.00 s (limit max_slowdown 1.2)");
  SceneResult within = timed(10, {11.5, 12.5, 13});  // 15 % slower: within the default
  judge_render_time(within, {});
  EXPECT_EQ(within.verdict, Verdict::Pass);
}

TEST(RenderTime, OneSlowRepeatIsNoise) {
  SceneResult s = timed(10, {25, 10.5, 11});
  judge_render_time(s, {});
  EXPECT_EQ(s.verdict, Verdict::Pass);
  EXPECT_EQ(s.new_seconds, 11);
  EXPECT_TRUE(s.reasons.empty());
}

TEST(RenderTime, TheHistoryMustAgree) {
  SceneResult slower = timed(10, {14});
  judge_render_time(slower, {}, 13.0);  // recent runs were already this slow: not a new slowdown
  EXPECT_EQ(slower.verdict, Verdict::Pass);
  SceneResult both = timed(10, {14});
  judge_render_time(both, {}, 10.0);
  EXPECT_EQ(both.verdict, Verdict::Regressed);
  EXPECT_NE(both.reasons[0].find("and 1.40x the recent median 10.00 s"), std::string::npos)
      << both.reasons[0];
}

TEST(RenderTime, ReusedOrUntimedScenesAreNotJudged) {
  SceneResult reused = timed(10, {100});
  reused.reused = true;
  judge_render_time(reused, {});
  EXPECT_EQ(reused.verdict, Verdict::Pass);
  SceneResult untimed = timed(0, {100});
  judge_render_time(untimed, {});
  EXPECT_EQ(untimed.verdict, Verdict::Pass);
  SceneResult single;
  single.golden_seconds = 1;
  single.new_seconds = 2;  // no repeats: the one timing
  judge_render_time(single, {});
  EXPECT_EQ(single.verdict, Verdict::Regressed);
}

TEST(Verdicts, RollUpToTheWorst) {
  EXPECT_EQ(worse(Verdict::Pass, Verdict::Regressed), Verdict::Regressed);
  EXPECT_EQ(worse(Verdict::Error, Verdict::Regressed), Verdict::Error);
  RunResult run;
  run.scenes = {timed(1, {}), error_result("smoke", "no golden")};
  summarize_run(run);
  EXPECT_EQ(run.verdict, Verdict::Error);
  EXPECT_EQ(run.scenes[1].name, "smoke");
  EXPECT_EQ(run.scenes[1].reasons, std::vector<std::string>{"no golden"});
}

}  // namespace
}  // namespace vesper::regress
