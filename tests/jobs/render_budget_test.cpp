// Noise targets and time limits in the job store: how a frame's budget is
// shared among its sample-range tasks, the budget stored with the job and
// carried by each lease, result reuse keyed on it, and the noise each frame's
// output reached, recorded once.
#include "jobs/render_budget.h"

#include <gtest/gtest.h>

#include <cmath>

#include "jobs/job_store.h"
#include "jobs/result_reuse.h"
#include "tests/common/temp_dir.h"

namespace vesper {
namespace {

RenderBudget budget(std::optional<double> noise, std::optional<int> min_spp = std::nullopt,
                    std::optional<double> seconds = std::nullopt) {
  return RenderBudget{noise, min_spp, seconds};
}

TEST(TaskBudget, AWholeFrameKeepsItsBudgetWithMinSppMadeExplicit) {
  const RenderBudget t = task_budget(budget(0.02, std::nullopt, 30.0), 256, 0, 256);
  EXPECT_EQ(t.noise_target, 0.02);
  EXPECT_EQ(t.min_spp, 16);  // the renderer's default, min(16, spp)
  EXPECT_EQ(t.time_limit, 30.0);
  EXPECT_EQ(task_budget(budget(0.02), 8, 0, 8).min_spp, 8);
  EXPECT_EQ(task_budget(budget(0.02, 4), 8, 0, 8).min_spp, 4);
}

TEST(TaskBudget, JEqualTasksEachAimAtXTimesSqrtJ) {
  // J independent estimates averaged: the mean's variance is 1/J of each one's,
  // so each may be sqrt(J) times noisier.
  for (int j : {1, 2, 4, 8, 16}) {
    const int spp = 1024, per_task = spp / j;
    for (int begin = 0; begin < spp; begin += per_task) {
      const RenderBudget t = task_budget(budget(0.01), spp, begin, begin + per_task);
      ASSERT_TRUE(t.noise_target);
      EXPECT_NEAR(*t.noise_target, 0.01 * std::sqrt(double(j)), 1e-15) << j;
    }
  }
}

TEST(TaskBudget, UnequalTasksShareByTheirSamples) {
  // 100 spp in tasks of 64: [0, 64) and [64, 100). Each task's target is
  // X / sqrt(share), so each takes its share of the samples the unsplit frame
  // would: the merged variance is that of the unsplit frame.
  const RenderBudget a = task_budget(budget(0.05, 40, 10.0), 100, 0, 64);
  const RenderBudget b = task_budget(budget(0.05, 40, 10.0), 100, 64, 100);
  EXPECT_NEAR(*a.noise_target, 0.05 / std::sqrt(0.64), 1e-15);
  EXPECT_NEAR(*b.noise_target, 0.05 / std::sqrt(0.36), 1e-15);
  const double inverse_variance =
      1 / (*a.noise_target * *a.noise_target) + 1 / (*b.noise_target * *b.noise_target);
  EXPECT_NEAR(inverse_variance, 1 / (0.05 * 0.05), 1e-9);
  // Each task keeps the frame's min spp (as far as its range allows), so
  // the merged frame has at least min_spp samples a pixel.
  EXPECT_EQ(a.min_spp, 40);
  EXPECT_EQ(b.min_spp, 36);
  // The frame's seconds are shared by samples: the same total however split.
  EXPECT_NEAR(*a.time_limit + *b.time_limit, 10.0, 1e-12);
  EXPECT_NEAR(*a.time_limit, 6.4, 1e-12);
}

TEST(TaskBudget, ATimeLimitAloneIsSharedAndNothingElseIsSet) {
  const RenderBudget t = task_budget(budget(std::nullopt, std::nullopt, 8.0), 64, 16, 32);
  EXPECT_FALSE(t.noise_target);
  EXPECT_FALSE(t.min_spp);
  EXPECT_EQ(t.time_limit, 2.0);
  EXPECT_TRUE(task_budget(RenderBudget{}, 64, 0, 32).empty());
  EXPECT_THROW(task_budget(budget(0.1), 64, 32, 32), std::invalid_argument);
  EXPECT_THROW(task_budget(budget(0.1), 64, 32, 65), std::invalid_argument);
}

TEST(BudgetProblem, NamesTheFieldAtFault) {
  auto field = [](const RenderBudget& b, int spp) -> std::string {
    const auto p = budget_problem(b, spp);
    return p ? p->field : "";
  };
  EXPECT_EQ(field(budget(0.01, 16, 10.0), 16), "");
  EXPECT_EQ(field(RenderBudget{}, 1), "");
  EXPECT_EQ(field(budget(0.0), 16), "noise_target");
  EXPECT_EQ(field(budget(-0.5), 16), "noise_target");
  EXPECT_EQ(field(budget(INFINITY), 16), "noise_target");
  EXPECT_EQ(field(budget(std::nullopt, 4), 16), "min_spp");
  EXPECT_EQ(field(budget(0.01, 17), 16), "min_spp");  // min_spp > max_spp
  EXPECT_EQ(field(budget(0.01, 0), 16), "min_spp");
  EXPECT_EQ(field(budget(0.01, std::nullopt, 0.0), 16), "time_limit");
  EXPECT_EQ(field(budget(std::nullopt, std::nullopt, -3.0), 16), "time_limit");
  EXPECT_NE(budget_problem(budget(0.01, 17), 16)->message.find("[1, 16]"), std::string::npos);
}

class BudgetStoreTest : public ::testing::Test {
 protected:
  static JobSpec spec(int spp, int split, RenderBudget b) {
    return JobSpec{"job", "scene-sha", {1}, spp, split, 50, 3, {}, b, {}, {}, {}};
  }
  std::filesystem::path db() const { return dir_ / "jobs.sqlite"; }
  test::TempDir dir_{"jobs"};
};

TEST_F(BudgetStoreTest, EachLeaseCarriesItsTasksShareOfTheFrameBudget) {
  JobStore s(db());
  s.submit(spec(256, 64, budget(0.02, 32, 60.0)), 0);
  for (int i = 0; i < 4; ++i) {
    const auto l = s.lease("w", 1);
    ASSERT_TRUE(l);
    EXPECT_EQ(l->spp, 256);
    EXPECT_NEAR(*l->budget.noise_target, 0.04, 1e-15);  // 0.02 * sqrt(4)
    EXPECT_EQ(l->budget.min_spp, 32);
    EXPECT_NEAR(*l->budget.time_limit, 15.0, 1e-12);
  }
  s.submit(spec(16, 0, RenderBudget{}), 0);
  const auto plain = s.lease("w", 1);
  ASSERT_TRUE(plain);
  EXPECT_TRUE(plain->budget.empty());
}

TEST_F(BudgetStoreTest, ABadBudgetIsRefusedNamingTheField) {
  JobStore s(db());
  auto error_of = [&](const JobSpec& sp) -> std::string {
    try {
      s.submit(sp, 0);
    } catch (const StoreError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error_of(spec(16, 0, budget(0.0))).find("noise_target"), std::string::npos);
  EXPECT_NE(error_of(spec(16, 0, budget(-1.0))).find("noise_target"), std::string::npos);
  EXPECT_NE(error_of(spec(16, 0, budget(NAN))).find("noise_target"), std::string::npos);
  EXPECT_NE(error_of(spec(16, 0, budget(std::nullopt, 4))).find("min_spp needs a noise_target"),
            std::string::npos);
  EXPECT_NE(error_of(spec(16, 0, budget(0.1, 17))).find("min_spp"), std::string::npos);
  EXPECT_NE(error_of(spec(16, 0, budget(0.1, 0))).find("min_spp"), std::string::npos);
  EXPECT_NE(error_of(spec(16, 0, budget(std::nullopt, std::nullopt, 0.0))).find("time_limit"),
            std::string::npos);
  EXPECT_TRUE(s.jobs().empty());
}

TEST_F(BudgetStoreTest, ResultReuseDistinguishesNoiseTargetsMinSppAndTimeLimits) {
  const JobSpec base = spec(64, 0, budget(0.02));
  EXPECT_EQ(inputs_key(base), inputs_key(spec(64, 0, budget(0.02))));
  EXPECT_NE(inputs_key(base), inputs_key(spec(64, 0, budget(0.03))));
  EXPECT_NE(inputs_key(base), inputs_key(spec(64, 0, budget(std::nextafter(0.02, 1.0)))));
  EXPECT_NE(inputs_key(base), inputs_key(spec(64, 0, budget(0.02, 8))));
  EXPECT_NE(inputs_key(base), inputs_key(spec(64, 0, budget(0.02, std::nullopt, 5.0))));
  EXPECT_NE(inputs_key(base), inputs_key(spec(64, 0, RenderBudget{})));
  // A job without a budget keeps the key it had before budgets existed.
  EXPECT_EQ(inputs_key(spec(64, 0, RenderBudget{})), "scene-sha;spp=64");

  JobStore s(db());
  s.submit(base, 0);
  const auto first = s.lease("w", 1, "r1");
  ASSERT_TRUE(first);
  ASSERT_TRUE(s.complete(first->lease_id, "noisy-0.02", 2));
  // Another noise target: rendered again, not reused.
  const int64_t other = s.submit(spec(64, 0, budget(0.01)), 3);
  int reused = -1;
  const auto second = s.lease("w", 4, "r1", &reused);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->task.job_id, other);
  EXPECT_EQ(reused, 0);
  // The same target: reused.
  const int64_t same = s.submit(base, 5);
  EXPECT_FALSE(s.lease("w", 6, "r1", &reused));
  EXPECT_EQ(reused, 1);
  EXPECT_EQ(s.frame(same, 1)->output, "noisy-0.02");
}

// A merged frame's output and its noise are one commit: a second connection
// (the API's reader) never sees the output without the noise.
TEST_F(BudgetStoreTest, AMergedOutputAndItsNoiseAreRecordedTogether) {
  JobStore s(db());
  const int64_t j = s.submit(spec(64, 32, budget(0.02)), 0);
  for (int i = 0; i < 2; ++i) {
    const auto l = s.lease("w", 1);
    ASSERT_TRUE(l);
    ASSERT_TRUE(s.complete(l->lease_id, "part-" + std::to_string(i), 2));
  }
  JobStore reader(db());
  EXPECT_EQ(reader.frame(j, 1)->output, "");
  const FrameNoise noise{0.0187, 41.25, "noise_target"};
  EXPECT_EQ(s.record_frame_output(j, 1, "merged", 3, noise), "merged");
  EXPECT_EQ(reader.frame(j, 1)->output, "merged");
  EXPECT_EQ(reader.frame(j, 1)->noise, noise);
  EXPECT_TRUE(s.outputs_without_noise().empty());
}

TEST_F(BudgetStoreTest, AFramesNoiseIsRecordedOnceAndTravelsWithAReusedOutput) {
  JobStore s(db());
  const int64_t j = s.submit(spec(64, 0, budget(0.02)), 0);
  EXPECT_TRUE(s.outputs_without_noise().empty());
  EXPECT_THROW(s.record_frame_noise(j, 1, {}), StoreError);  // no output yet
  const auto l = s.lease("w", 1, "r1");
  ASSERT_TRUE(s.complete(l->lease_id, "exr-1", 2));
  const auto unread = s.outputs_without_noise();
  ASSERT_EQ(unread.size(), 1u);
  EXPECT_EQ(unread[0].job, j);
  EXPECT_EQ(unread[0].frame, 1);
  EXPECT_EQ(unread[0].blob, "exr-1");
  EXPECT_FALSE(s.frame(j, 1)->noise);

  const FrameNoise noise{0.0183, 41.5, "noise_target"};
  s.record_frame_noise(j, 1, noise);
  EXPECT_EQ(s.frame(j, 1)->noise, noise);
  EXPECT_TRUE(s.outputs_without_noise().empty());
  s.record_frame_noise(j, 1, FrameNoise{0.5, 2.0, "spp"});  // once: kept
  EXPECT_EQ(s.frames(j).at(0).noise, noise);

  // The same result reused by an identical job: its frame has the noise at once.
  const int64_t again = s.submit(spec(64, 0, budget(0.02)), 3);
  EXPECT_FALSE(s.lease("w", 4, "r1"));
  EXPECT_EQ(s.frame(again, 1)->output, "exr-1");
  EXPECT_EQ(s.frame(again, 1)->noise, noise);
  EXPECT_TRUE(s.outputs_without_noise().empty());

  // A completion can bring its result's noise: a one-task frame records it
  // with its output; a task of a split frame has no output to give it to.
  const int64_t direct = s.submit(spec(32, 0, budget(0.05)), 5);
  const int64_t split = s.submit(spec(32, 16, budget(0.05)), 5);
  const FrameNoise said{0.04, 12.0, "noise_target"};
  for (int i = 0; i < 3; ++i) {
    const auto t = s.lease("w", 6);
    ASSERT_TRUE(t);
    ASSERT_TRUE(s.complete(t->lease_id, "out-" + std::to_string(t->task.id), 7, said));
  }
  EXPECT_EQ(s.frame(direct, 1)->noise, said);
  EXPECT_FALSE(s.frame(split, 1)->noise);  // its merge will have its own
  EXPECT_EQ(s.frame(split, 1)->output, "");

  // An output that says nothing of its noise is read once all the same.
  const int64_t plain = s.submit(spec(8, 0, RenderBudget{}), 5);
  const auto p = s.lease("w", 6);
  ASSERT_TRUE(s.complete(p->lease_id, "plain-exr", 7));
  s.record_frame_noise(plain, 1, FrameNoise{});
  EXPECT_EQ(s.frame(plain, 1)->noise, FrameNoise{});
  EXPECT_TRUE(s.outputs_without_noise().empty());
}

}  // namespace
}  // namespace vesper
