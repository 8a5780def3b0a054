// launch.record: what lcm-logger writes into RUN/bus.lcmlog, with the real simulator and
// lcm-logger. Ports 47174-47176.

#include <gtest/gtest.h>
#include <lcm/eventlog.h>

#include <map>

#include "launch_harness.hpp"

namespace relplane::testing {
namespace {

constexpr int kIterations = 10;

// Messages per channel in a log.
std::map<std::string, int> ChannelCounts(const std::string& path) {
  std::map<std::string, int> counts;
  lcm_eventlog_t* log = lcm_eventlog_create(path.c_str(), "r");
  if (!log) {
    ADD_FAILURE() << "cannot open " << path;
    return counts;
  }
  while (lcm_eventlog_event_t* event = lcm_eventlog_read_next_event(log)) {
    ++counts[event->channel];
    lcm_eventlog_free_event(event);
  }
  lcm_eventlog_destroy(log);
  return counts;
}

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
  EXPECT_EQ(counts.count("SENSOR_POINTS") ? counts.at("SENSOR_POINTS") : 0, kIterations);
  EXPECT_EQ(counts.count("SIM_TRUTH") ? counts.at("SIM_TRUTH") : 0, kIterations);
  EXPECT_GT(counts.count("SIM_WORLD"), 0u);
}

TEST(Record, WithoutCloudsIsEveryChannelButSensorPoints) {
  TempDir dir;
  const auto counts = ChannelCounts(RunRecording(dir, "without_clouds", 47175) + "/bus.lcmlog");
  EXPECT_EQ(counts.count("SENSOR_POINTS"), 0u);
  EXPECT_EQ(counts.count("SIM_TRUTH") ? counts.at("SIM_TRUTH") : 0, kIterations);
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
