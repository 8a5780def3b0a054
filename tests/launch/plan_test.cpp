#include "plan.hpp"

#include <gtest/gtest.h>
#include <regex.h>
#include <signal.h>
#include <sys/wait.h>

#include "lines.hpp"

namespace relplane::launch {
namespace {

TEST(StopOrderTest, SourceFirstThenPipelineFromItsHead) {
  EXPECT_EQ(StopOrder({"logger", "mapper", "sim", "segmenter"}),
            (std::vector<std::string>{"sim", "segmenter", "mapper", "logger"}));
  EXPECT_EQ(StopOrder({"extra", "mapper", "sim"}),
            (std::vector<std::string>{"sim", "mapper", "extra"}));
  EXPECT_TRUE(StopOrder({}).empty());
}

TEST(StopOrderTest, AReplaySourceStopsFirstToo) {
  EXPECT_EQ(StopOrder({"segmenter", "mapper", "logger", kReplaySource}, kReplaySource),
            (std::vector<std::string>{kReplaySource, "segmenter", "mapper", "logger"}));
  EXPECT_EQ(StartOrder({kReplaySource, "segmenter", "logger"}, kReplaySource),
            (std::vector<std::string>{"segmenter", "logger", kReplaySource}));
}

TEST(ReplayCommandTest, PlaysOnlyTheSimulatorChannelsOnTheRunBus) {
  const ChildSpec player =
      ReplayCommand("/usr/bin/lcm-logplayer", "udpm://g:5", "/r/bus.lcmlog", 2);
  EXPECT_EQ(player.name, kReplaySource);
  EXPECT_EQ(player.argv,
            (std::vector<std::string>{"/usr/bin/lcm-logplayer", "--speed=2",
                                      "--regexp=^(SENSOR_POINTS|SIM_TRUTH|SIM_WORLD|ODOMETRY)$",
                                      "--lcm-url=udpm://g:5", "/r/bus.lcmlog"}));
}

TEST(StartOrderTest, SourceLastSoSubscribersHearItsFirstMessage) {
  EXPECT_EQ(StartOrder({"sim", "segmenter", "mapper", "logger"}),
            (std::vector<std::string>{"segmenter", "mapper", "logger", "sim"}));
  EXPECT_EQ(StartOrder({"mapper"}), std::vector<std::string>{"mapper"});
}

TEST(ServiceCommandTest, ConfigUrlAndPerServiceFlags) {
  LaunchOptions options;
  const ChildSpec mapper =
      ServiceCommand("mapper", "/b", "/r/scenario.yaml", "udpm://x:1", "/r", options);
  EXPECT_EQ(mapper.argv, (std::vector<std::string>{"/b/relplane-mapper", "--config",
                                                   "/r/scenario.yaml", "--lcm-url", "udpm://x:1",
                                                   "--checkpoint", "/r/mapper.journal"}));
  const ChildSpec logger = ServiceCommand("logger", "/b", "/r/s.yaml", "u", "/r", options);
  EXPECT_EQ(logger.argv.back(), "/r");
  EXPECT_EQ(logger.argv[logger.argv.size() - 2], "--out");

  EXPECT_EQ(ServiceCommand("sim", "/b", "s", "u", "/r", options).argv.size(), 5u);
  options.rate_hz = 0;
  const ChildSpec sim = ServiceCommand("sim", "/b", "s", "u", "/r", options);
  EXPECT_EQ(sim.argv[sim.argv.size() - 2], "--rate");
  EXPECT_EQ(sim.argv.back(), "0");
  const ChildSpec short_sim = ServiceCommand("sim", "/b", "s", "u", "/r", options, 12);
  EXPECT_EQ(short_sim.argv[short_sim.argv.size() - 2], "--iterations");
  EXPECT_EQ(short_sim.argv.back(), "12");
  EXPECT_EQ(ServiceCommand("mapper", "/b", "s", "u", "/r", options, 12).argv.size(), 7u);
}

TEST(RecorderCommandTest, UsesTheLongUrlFlag) {
  const ChildSpec recorder = RecorderCommand("/usr/bin/lcm-logger", "udpm://g:5", "/r");
  EXPECT_EQ(recorder.argv, (std::vector<std::string>{"/usr/bin/lcm-logger", "--lcm-url=udpm://g:5",
                                                     "--force", "--quiet", "/r/bus.lcmlog"}));
}

TEST(RecorderCommandTest, WithoutCloudsRecordsEveryChannelButSensorPoints) {
  const ChildSpec recorder =
      RecorderCommand("/usr/bin/lcm-logger", "udpm://g:5", "/r", kRecordWithoutClouds);
  ASSERT_EQ(recorder.argv.size(), 6u);
  EXPECT_EQ(recorder.argv[4], "--channel=" + EveryChannelBut("SENSOR_POINTS"));
  EXPECT_EQ(recorder.argv[5], "/r/bus.lcmlog");
}

// As lcm-logger uses it: a POSIX extended expression anchored as ^...$.
bool Matches(const std::string& expression, const std::string& name) {
  regex_t regex;
  EXPECT_EQ(regcomp(&regex, ("^" + expression + "$").c_str(), REG_EXTENDED | REG_NOSUB), 0);
  const bool match = regexec(&regex, name.c_str(), 0, nullptr, 0) == 0;
  regfree(&regex);
  return match;
}

TEST(EveryChannelButTest, MatchesEveryNameButTheOne) {
  const std::string expression = EveryChannelBut("SENSOR_POINTS");
  EXPECT_FALSE(Matches(expression, "SENSOR_POINTS"));
  for (const char* name :
       {"POSE", "MAP", "PLANES", "SIM_TRUTH", "SIM_WORLD", "STATUS", "ODOMETRY", "S",
        "SENSOR_POINT", "SENSOR_POINTS2", "SENSOR_POINTSX_Y", "XSENSOR_POINTS", "SENSOR_points"}) {
    EXPECT_TRUE(Matches(expression, name)) << name;
  }
}

TEST(DefaultRunDirTest, NameAndUtcTimestamp) {
  EXPECT_EQ(DefaultRunDir("runs", "hallway_loop", 1795426530),
            "runs/hallway_loop-20261123T093530Z");
}

TEST(DescribeExitTest, CodesAndSignals) {
  EXPECT_EQ(DescribeExit(3 << 8), "exited with code 3");
  const std::string killed = DescribeExit(SIGKILL);
  EXPECT_EQ(killed.rfind("was killed by signal 9", 0), 0u) << killed;
}

TEST(LineSplitterTest, WholeLinesAcrossChunks) {
  LineSplitter splitter;
  EXPECT_TRUE(splitter.Feed("hel", 3).empty());
  EXPECT_EQ(splitter.Feed("lo\r\nwor", 7), std::vector<std::string>{"hello"});
  EXPECT_EQ(splitter.Feed("ld\n\n", 4), (std::vector<std::string>{"world", ""}));
  EXPECT_TRUE(splitter.Flush().empty());
  splitter.Feed("tail", 4);
  EXPECT_EQ(splitter.Flush(), std::vector<std::string>{"tail"});
}

TEST(LineSplitterTest, OverlongLinesAreCut) {
  LineSplitter splitter;
  const std::string big(LineSplitter::kMaxLine + 10, 'x');
  const auto lines = splitter.Feed(big.data(), big.size());
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].size(), LineSplitter::kMaxLine);
  EXPECT_EQ(splitter.Flush()[0].size(), 10u);
}

}  // namespace
}  // namespace relplane::launch
