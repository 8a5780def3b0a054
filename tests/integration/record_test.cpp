// launch.record: what lcm-logger writes into RUN/bus.lcmlog, with the real simulator and
// lcm-logger. Ports 47174-47176.

#include <gtest/gtest.h>

#include <map>

#include "launch_harness.hpp"
#include "log_counts.hpp"

namespace relplane::testing {
namespace {

constexpr int kIterations = 10;

// A short simulator-only run of straight_hallway recording `record`; returns the run folder.
std::string RunRecording(const TempDir& dir, const std::string& record, int port) {
  const std::string run = dir.Path() + "/run";
  std::string output;
  EXPECT_EQ(
      RunLauncher({SourceDir() + "/scenarios/straight_hallway.yaml", "--out", run, "--lcm-url",
                   TestBusUrl(port), "--set", "launch.services=[sim]", "--set", "launch.rate_hz=60",
                   "--set", "launch.record=" + record, "--iterations", std::to_string(kIterations)},
                  60, &output),
      0)
      << output;
  return run;
}

TEST(Record, AllIsEveryChannel) {
  TempDir dir;
  const auto counts = ChannelCounts(RunRecording(dir, "all", 47174) + "/bus.lcmlog");
  EXPECT_EQ(CountOf(counts, "SENSOR_POINTS"), kIterations);
  EXPECT_EQ(CountOf(counts, "SIM_TRUTH"), kIterations);
  EXPECT_GT(counts.count("SIM_WORLD"), 0u);
}

TEST(Record, WithoutCloudsIsEveryChannelButSensorPoints) {
  TempDir dir;
  const auto counts = ChannelCounts(RunRecording(dir, "without_clouds", 47175) + "/bus.lcmlog");
  EXPECT_EQ(counts.count("SENSOR_POINTS"), 0u);
  EXPECT_EQ(CountOf(counts, "SIM_TRUTH"), kIterations);
  EXPECT_GT(counts.count("SIM_WORLD"), 0u);
  EXPECT_GT(counts.count("STATUS"), 0u);
}

TEST(Record, NothingLeavesNoLog) {
  TempDir dir;
  const std::string run = RunRecording(dir, "nothing", 47176);
  EXPECT_TRUE(Exists(run + "/scenario.yaml"));
  EXPECT_FALSE(Exists(run + "/bus.lcmlog"));
}

}  // namespace
}  // namespace relplane::testing
