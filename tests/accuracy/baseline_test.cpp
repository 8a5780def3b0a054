// A sweep compared with an earlier one read back from its --json (baseline.hpp).
#include "relplane/accuracy/baseline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace relplane::accuracy {
namespace {

SweepRun Sweep(const std::string& scenario, uint64_t seed, double ate) {
  SweepRun run;
  run.scenario = scenario;
  run.seed = seed;
  run.result.frames = 100;
  run.result.trajectory.matched = 100;
  run.result.trajectory.ate_rmse_m = ate;
  run.result.map.walls_mapped = 5;
  run.result.map.normal_error_deg.max = 0.5;
  run.result.map.offset_error_m.max = 0.03;
  run.misses = Misses(run.result, Targets{});
  return run;
}

TEST(Baseline, ReadsBackWhatTheSweepWrote) {
  SweepRun lost = Sweep("office", 4, std::numeric_limits<double>::quiet_NaN());
  const std::vector<SweepRun> runs = {Sweep("office", 3, 0.0125), Sweep("office", 7, 0.0625), lost};
  const std::vector<BaselineRun> b = ParseBaseline(SweepJson(runs, Targets{}, {}));
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].scenario, "office");
  EXPECT_EQ(b[0].seed, 3u);
  EXPECT_TRUE(b[0].meets_targets);
  EXPECT_DOUBLE_EQ(b[0].ate_rmse_m, 0.0125);
  EXPECT_FALSE(b[1].meets_targets);  // ATE over 5 cm
  EXPECT_DOUBLE_EQ(b[1].ate_rmse_m, 0.0625);
  // Nothing to score is written as null and read back as no number, not as a good one.
  EXPECT_FALSE(b[2].meets_targets);
  EXPECT_TRUE(std::isnan(b[2].ate_rmse_m));
}

TEST(Baseline, WhatIsNoSweepIsOneLineSayingWhy) {
  const auto reason = [](const std::string& text) {
    try {
      ParseBaseline(text);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(reason("{\"runs\": [1,").find("not JSON"), std::string::npos);
  EXPECT_NE(reason("{\"frames\": 3}").find("no \"runs\" list"), std::string::npos);
  EXPECT_NE(reason("{\"runs\": [{\"scenario\": \"office\", \"seed\": 2}]}").find("run 1 lacks"),
            std::string::npos);
  try {
    ReadBaseline("/no/such/dir/sweep.json");
    ADD_FAILURE() << "a missing file was read";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot read /no/such/dir/sweep.json");
  }
}

TEST(Baseline, ComparesRunByRunOverTheRunsBothHold) {
  const std::vector<BaselineRun> before = {
      {"office", 1, true, 0.010}, {"office", 2, false, 0.060}, {"office", 3, true, 0.020},
      {"office", 4, true, 0.030}, {"loop", 1, true, 0.015},
  };
  const std::vector<SweepRun> after = {
      Sweep("office", 1, 0.0102),  // within a millimetre: unchanged
      Sweep("office", 2, 0.030),   // now met
      Sweep("office", 3, 0.070),   // now missed
      Sweep("office", 4, 0.036),   // worse, still met
      Sweep("loop", 1, 0.012),     // better
      Sweep("office", 9, 0.010),   // not in the baseline
  };
  const BaselineComparison c = CompareWithBaseline(before, after);
  EXPECT_EQ(c.common, 5);
  EXPECT_EQ(c.not_in_baseline, 1);
  EXPECT_EQ(c.meeting_before, 4);
  EXPECT_EQ(c.meeting_after, 4);
  EXPECT_NEAR(c.ate_sum_before_m, 0.135, 1e-12);
  EXPECT_NEAR(c.ate_sum_after_m, 0.1582, 1e-12);
  EXPECT_EQ(c.better, 2);
  EXPECT_EQ(c.worse, 2);
  ASSERT_EQ(c.now_met.size(), 1u);
  EXPECT_EQ(c.now_met[0].seed, 2u);
  ASSERT_EQ(c.now_missed.size(), 1u);
  EXPECT_EQ(c.now_missed[0].seed, 3u);
  ASSERT_EQ(c.most_worse.size(), 2u);  // the largest increase first
  EXPECT_EQ(c.most_worse[0].seed, 3u);
  EXPECT_EQ(c.most_worse[1].seed, 4u);

  const std::string text = ComparisonText(c, "before.json");
  EXPECT_NE(text.find("against before.json, 5 runs in both: meeting 4 -> 4, ATE sum 0.135 m -> "
                      "0.158 m"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("now met: office 2 (ATE 0.060 m -> 0.030 m)"), std::string::npos) << text;
  EXPECT_NE(text.find("now missed: office 3 (ATE 0.020 m -> 0.070 m; ATE 0.070 m)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("1 runs not in the baseline"), std::string::npos) << text;
  EXPECT_NE(text.find("worse on 2; the most: office 3 0.020 m -> 0.070 m, office 4"),
            std::string::npos)
      << text;
}

}  // namespace
}  // namespace relplane::accuracy
