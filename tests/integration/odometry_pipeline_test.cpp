// Wheel odometry through the real processes (issue 51): relplane-sim publishes ODOMETRY, the
// mapper service integrates it between plane sets and the mapper predicts with it where the
// walls leave a direction open. Port 47180-47181.
// hallway_loop's first leg: for its first ~7 m only the two parallel side walls are in view, so
// without odometry nothing fixes the position along the hallway (the estimate stands still
// while the robot drives on); with odometry it follows, within odometry's own drift.

#include <gtest/gtest.h>

#include <string>

#include "launch_harness.hpp"

namespace relplane::testing {
namespace {

double Number(const std::string& text, const std::string& key) {
  const std::vector<std::string> match = RegexSearch(text, "\"" + key + "\": (-?[0-9.eE+-]+)");
  return match.empty() ? -1 : std::stod(match[1]);
}

// ATE RMSE of the first `iterations` of hallway_loop_odometry, odometry on or off.
double FirstLegAte(bool odometry, int port, std::string* metrics) {
  TempDir dir;
  std::string output;
  const int code =
      RunLauncher({SourceDir() + "/scenarios/hallway_loop_odometry.yaml", "--out",
                   dir.Path() + "/run", "--lcm-url", TestBusUrl(port), "--iterations", "150",
                   "--set", std::string("sim.odometry.enabled=") + (odometry ? "true" : "false"),
                   "--set", "expect={lost_max: 0}"},
                  120, &output);
  *metrics = ReadText(dir.Path() + "/run/metrics.json");
  EXPECT_EQ(code, 0) << output;
  return Number(*metrics, "ate_rmse_m");
}

TEST(OdometryPipeline, CarriesThePositionAlongAFeaturelessHallway) {
  std::string with_metrics, without_metrics;
  const double with = FirstLegAte(true, 47180, &with_metrics);
  const double without = FirstLegAte(false, 47181, &without_metrics);
  // 150 iterations at 1.5 m/s is 7.5 m: standing still, the estimate ends metres behind.
  ASSERT_GT(without, 1.0) << "the first leg was observable without odometry: the test shows "
                             "nothing\n"
                          << without_metrics;
  // Within the simulated odometry's 1 % over the leg, with half again for margin.
  EXPECT_GE(with, 0.0) << with_metrics;
  EXPECT_LT(with, 0.015 * 7.5) << with_metrics;
}

}  // namespace
}  // namespace relplane::testing
