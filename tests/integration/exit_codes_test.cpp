// relplane-launch's exit codes with the real simulator and logger (README "Exit codes"): 0 when
// the run completed and every expectation held (or the scenario expects nothing), 3 when it
// completed but an expectation failed, 2 for a scenario or --set that is wrong, nothing started.
// Exit 1 (a child died) and 130 (interrupted) are pinned by launch_supervision_test.
// Ports 47170-47172.

#include <gtest/gtest.h>

#include "launch_harness.hpp"

namespace relplane::testing {
namespace {

std::string Scenario() { return SourceDir() + "/scenarios/straight_hallway.yaml"; }

// Ten frames of the simulator, scored by the real logger: no mapper, so no POSE.
std::vector<std::string> ShortRun(const std::string& out, int port) {
  return {Scenario(),
          "--out",
          out,
          "--lcm-url",
          TestBusUrl(port),
          "--set",
          "launch.services=[sim, logger]",
          "--set",
          "launch.rate_hz=0",
          "--iterations",
          "10"};
}

TEST(ExitCodes, AFailedExpectationExitsThreeNamingIt) {
  TempDir dir;
  std::vector<std::string> args = ShortRun(dir.Path() + "/run", 47170);
  args.insert(args.end(), {"--set", "expect={iterations_min: 5, lost_max: 0}"});
  std::string output;
  EXPECT_EQ(RunLauncher(args, 60, &output), 3) << output;
  EXPECT_NE(output.find("[launch] FAIL: 1 of 2 expectations failed: iterations_min 0 < 5; run "
                        "folder " +
                        dir.Path() + "/run"),
            std::string::npos)
      << output;
  EXPECT_TRUE(Exists(dir.Path() + "/run/metrics.json"));
}

TEST(ExitCodes, AScenarioExpectingNothingExitsZeroWithoutVerdict) {
  TempDir dir;
  std::vector<std::string> args = ShortRun(dir.Path() + "/run", 47171);
  args.insert(args.end(), {"--set", "expect={}"});
  std::string output;
  EXPECT_EQ(RunLauncher(args, 60, &output), 0) << output;
  EXPECT_NE(output.find("[launch] no verdict: the scenario has no expect: section"),
            std::string::npos)
      << output;
}

TEST(ExitCodes, ASetErrorNamesTheScenarioAndTheKeyAndStartsNothing) {
  TempDir dir;
  std::string output;
  EXPECT_EQ(
      RunLauncher({"straight_hallway", "--out", dir.Path() + "/run", "--lcm-url", TestBusUrl(47172),
                   "--set", "launch.services=[sim, logger]", "--set", "sim.sensor.no_such_key=1"},
                  60, &output),
      2)
      << output;
  // A bare name is the project's scenario; the message points at it, not at a temporary file.
  EXPECT_EQ(
      output.rfind(
          Scenario() + " (after the --set overrides): unknown key 'sim.sensor.no_such_key'", 0),
      0u)
      << output;
  EXPECT_EQ(output.find("/tmp/relplane-scenario"), std::string::npos) << output;
  EXPECT_FALSE(Exists(dir.Path() + "/run"));
}

TEST(ExitCodes, AnUnknownScenarioNameIsAUsageError) {
  std::string output;
  EXPECT_EQ(RunLauncher({"no_such_scenario", "--check"}, 30, &output), 2) << output;
  EXPECT_EQ(output.rfind("no_such_scenario: no such scenario file (the project's: ", 0), 0u)
      << output;
}

}  // namespace
}  // namespace relplane::testing
