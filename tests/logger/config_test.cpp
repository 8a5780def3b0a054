// The logger section and expect: of a scenario, and expectation verdicts.
#include <gtest/gtest.h>

#include "options_yaml.hpp"
#include "relplane/common/options.hpp"
#include "relplane/eval/expectations.hpp"

namespace relplane::eval {
namespace {

TEST(EvalConfig, ReadsLoggerOptionsAndExpectations) {
  const EvalConfig c = ParseEvalConfig(
      "name: x\nsim: {rate_hz: 30}\n"
      "logger:\n  flush_period_s: 0.5\n  match: {angle_max_deg: 5}\n"
      "  visibility: {range_m: 4}\n"
      "expect:\n  ate_rmse_max_m: 0.05\n  walls_mapped_min: 8\n",
      "s.yaml");
  EXPECT_DOUBLE_EQ(c.options.flush_period_s, 0.5);
  EXPECT_DOUBLE_EQ(c.options.match.angle_max_deg, 5.0);
  EXPECT_DOUBLE_EQ(c.options.match.offset_max_m, 0.3);
  EXPECT_DOUBLE_EQ(c.options.visibility.range_m, 4.0);
  ASSERT_EQ(c.expect.size(), 2u);
  EXPECT_EQ(c.expect[0].key, "ate_rmse_max_m");
  EXPECT_DOUBLE_EQ(c.expect[0].limit, 0.05);
  EXPECT_EQ(c.expect[1].key, "walls_mapped_min");
}

// What counts as visible is what the simulated sensor sees, unless the logger says otherwise.
TEST(EvalConfig, VisibilityDefaultsToTheSimulatedSensor) {
  const EvalConfig c = ParseEvalConfig(
      "sim:\n  sensor: {max_range: 6, hfov_deg: 70, width: 200}\n  rate_hz: 30\n", "s.yaml");
  EXPECT_DOUBLE_EQ(c.options.visibility.range_m, 6.0);
  EXPECT_DOUBLE_EQ(c.options.visibility.hfov_deg, 70.0);
  const EvalConfig own = ParseEvalConfig(
      "sim:\n  sensor: {max_range: 6, hfov_deg: 70}\nlogger:\n  visibility: {range_m: 4}\n",
      "s.yaml");
  EXPECT_DOUBLE_EQ(own.options.visibility.range_m, 4.0);
  EXPECT_DOUBLE_EQ(own.options.visibility.hfov_deg, 70.0);
  const EvalConfig none = ParseEvalConfig("name: x\n", "s.yaml");
  EXPECT_DOUBLE_EQ(none.options.visibility.range_m, VisibilityOptions{}.range_m);
}

TEST(EvalConfig, UnknownOrBadKeysAreOneLineErrors) {
  try {
    ParseEvalConfig("expect:\n  ate_rmse_max: 0.05\n", "s.yaml");
    FAIL() << "an unknown expect key must be refused";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("s.yaml:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ate_rmse_max"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ParseEvalConfig("logger:\n  flush_period_s: -1\n", "s.yaml"), config::ConfigError);
  EXPECT_THROW(ParseEvalConfig("logger:\n  match: {angle_max: 3}\n", "s.yaml"),
               config::ConfigError);
  EXPECT_THROW(ParseEvalConfig("expect:\n  duplicates_max: many\n", "s.yaml"), config::ConfigError);
}

TEST(Expectations, MaxAndMinLimitsAndMissingData) {
  RunMetrics m;
  m.run.estimate_poses = 100;
  m.trajectory.ate_rmse_m = 0.04;
  m.map.has_truth = true;
  m.map.duplicates = 1;
  const std::vector<ExpectationResult> r = CheckExpectations({{"ate_rmse_max_m", 0.05},
                                                              {"duplicates_max", 0},
                                                              {"iterations_min", 100},
                                                              {"latency_p99_max_ms", 30}},
                                                             m);
  ASSERT_EQ(r.size(), 4u);
  EXPECT_TRUE(r[0].pass);
  EXPECT_FALSE(r[1].pass);
  EXPECT_TRUE(r[2].pass);
  EXPECT_FALSE(r[2].is_max);
  EXPECT_FALSE(r[3].pass);  // no latency measured: no data is a failure
  EXPECT_TRUE(std::isnan(r[3].value));
}

// hallway_loop cannot observe its position along its featureless legs: it expects a large ATE.
TEST(Expectations, AnUnobservableRunExpectsALargeAte) {
  RunMetrics m;
  m.trajectory.ate_rmse_m = 6.9;
  EXPECT_TRUE(CheckExpectations({{"ate_rmse_min_m", 1.0}}, m)[0].pass);
  m.trajectory.ate_rmse_m = 0.02;
  EXPECT_FALSE(CheckExpectations({{"ate_rmse_min_m", 1.0}}, m)[0].pass);
}

TEST(Expectations, EveryKeyHasAMetric) {
  RunMetrics m;
  m.map.has_truth = true;
  m.map.expected_walls = 1;
  m.trajectory.ate_rmse_m = m.trajectory.ate_aligned_rmse_m = m.trajectory.ate_final_m = 0;
  m.trajectory.yaw_rmse_deg = m.trajectory.rpe_translation_per_m = 0;
  m.map.normal_error_deg.max = m.map.offset_error_m.max = m.map.endpoint_error_m.max = 0;
  m.timing.end_to_end.p99_ms = 0;
  m.run.wall_rate_hz = 0;
  for (const ExpectationKey& k : ExpectationKeys()) {
    EXPECT_FALSE(std::isnan(ExpectationValue(k.key, m))) << k.key;
  }
}

}  // namespace
}  // namespace relplane::eval
