// The launcher's plan for clouds on a bus of their own: who gets --cloud-url, the two
// recorders and the two players of a replay; one bus for all when both URLs are the same.

#include <gtest/gtest.h>

#include "plan.hpp"

namespace relplane::launch {
namespace {

using Argv = std::vector<std::string>;

TEST(CloudBusPlanTest, OnlyTheServicesThatTouchCloudsJoinTheCloudBus) {
  const LaunchOptions options;
  for (const std::string name : {"sim", "segmenter"}) {
    const ChildSpec spec = WithCloudUrl(ServiceCommand(name, "/b", "s", "u", "/r", options), "u",
                                        "c");
    ASSERT_GE(spec.argv.size(), 2u);
    EXPECT_EQ(Argv(spec.argv.end() - 2, spec.argv.end()), (Argv{"--cloud-url", "c"})) << name;
  }
  for (const std::string name : {"mapper", "logger"}) {
    const ChildSpec plain = ServiceCommand(name, "/b", "s", "u", "/r", options);
    EXPECT_EQ(WithCloudUrl(plain, "u", "c").argv, plain.argv) << name;
  }
  // One URL for everything: command lines as without a cloud bus.
  const ChildSpec sim = ServiceCommand("sim", "/b", "s", "u", "/r", options);
  EXPECT_EQ(WithCloudUrl(sim, "u", "u").argv, sim.argv);
}

TEST(CloudBusPlanTest, ASecondRecorderOnTheCloudBusOnlyWhenThereIsOne) {
  const std::vector<ChildSpec> one = RecorderCommands("/l", "u", "u", "/r", kRecordAll);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].argv, RecorderCommand("/l", "u", "/r").argv);
  const std::vector<ChildSpec> two = RecorderCommands("/l", "u", "c", "/r", kRecordAll);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].argv, RecorderCommand("/l", "u", "/r").argv);
  EXPECT_EQ(two[1].name, kCloudRecorder);
  EXPECT_EQ(two[1].argv, (Argv{"/l", "--lcm-url=c", "--force", "--quiet", "/r/clouds.lcmlog"}));
}

TEST(CloudBusPlanTest, TheRecordSettingChoosesTheRecorders) {
  EXPECT_TRUE(RecorderCommands("/l", "u", "c", "/r", kRecordNothing).empty());
  // Without clouds: the main bus only, which with a cloud bus of its own carries none.
  const std::vector<ChildSpec> main_only = RecorderCommands("/l", "u", "c", "/r", kRecordWithoutClouds);
  ASSERT_EQ(main_only.size(), 1u);
  EXPECT_EQ(main_only[0].argv, RecorderCommand("/l", "u", "/r", kRecordWithoutClouds).argv);
}

TEST(CloudBusPlanTest, AReplayPlaysTheCloudsOntoTheCloudBusAndTheRestOntoTheMainBus) {
  const std::vector<ChildSpec> one = ReplayCommands("/p", "u", "u", "/x.lcmlog", 1);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].argv, ReplayCommand("/p", "u", "/x.lcmlog", 1).argv);
  const std::vector<ChildSpec> two = ReplayCommands("/p", "u", "c", "/x.lcmlog", 2);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].name, kReplaySimSource);
  EXPECT_EQ(two[0].argv, (Argv{"/p", "--speed=2", "--regexp=^(SIM_TRUTH|SIM_WORLD)$",
                               "--lcm-url=u", "/x.lcmlog"}));
  EXPECT_EQ(two[1].name, kReplaySource);  // the source, started last
  EXPECT_EQ(two[1].argv,
            (Argv{"/p", "--speed=2", "--regexp=^SENSOR_POINTS$", "--lcm-url=c", "/x.lcmlog"}));
}

}  // namespace
}  // namespace relplane::launch
