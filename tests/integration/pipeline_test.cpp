// The real services under relplane-launch: a service killed mid-run fails the run, and a
// recorded run replayed twice gives byte-identical results (issue 7). Each run on its own port.

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <thread>

#include "launch_harness.hpp"

namespace relplane::testing {
namespace {

std::string Scenario() { return SourceDir() + "/scenarios/straight_hallway.yaml"; }

// The pid of the live process running `program` on the bus `url`, waiting up to `timeout_s`.
pid_t FindService(const std::string& url, const std::string& program, double timeout_s) {
  for (int i = 0; i < static_cast<int>(timeout_s * 20); ++i) {
    for (pid_t pid : ProcessesWithEnvironment("LCM_DEFAULT_URL=" + url)) {
      char exe[4096];
      const ssize_t n =
          readlink(("/proc/" + std::to_string(pid) + "/exe").c_str(), exe, sizeof exe);
      if (n > 0 && std::string(exe, n).size() >= program.size() &&
          std::string(exe, n).compare(n - program.size(), program.size(), program) == 0) {
        return pid;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return -1;
}

TEST(Pipeline, KilledServiceFailsTheRun) {
  TempDir dir;
  const std::string url = TestBusUrl(47120);
  Launcher launcher({Scenario(), "--out", dir.Path() + "/run", "--lcm-url", url, "--set",
                     "launch.services=[sim, mapper, logger]"},
                    dir.Path() + "/out.txt");
  const pid_t mapper = FindService(url, "/relplane-mapper", 20);
  ASSERT_GT(mapper, 0) << launcher.Output();
  ASSERT_GT(FindService(url, "/relplane-sim", 20), 0) << launcher.Output();
  ASSERT_EQ(kill(mapper, SIGKILL), 0);
  EXPECT_EQ(launcher.Wait(60), 1) << launcher.Output();
  EXPECT_NE(launcher.Output().find("error: mapper was killed by signal 9"), std::string::npos)
      << launcher.Output();
  // The logger still wrote its files on the way out.
  EXPECT_TRUE(Exists(dir.Path() + "/run/metrics.json")) << launcher.Output();
  EXPECT_TRUE(ProcessesWithEnvironment("LCM_DEFAULT_URL=" + url).empty());
}

TEST(Pipeline, ReplayingALogTwiceGivesIdenticalResults) {
  TempDir dir;
  const std::string live = dir.Path() + "/live";
  std::string output;
  ASSERT_EQ(RunLauncher({Scenario(), "--out", live, "--lcm-url", TestBusUrl(47121), "--set",
                         "launch.services=[sim, segmenter, mapper, logger]", "--iterations", "150"},
                        180, &output),
            0)
      << output;
  std::string results[2][2];  // [replay][trajectory, map]
  for (int i = 0; i < 2; ++i) {
    const std::string out = dir.Path() + "/replay" + std::to_string(i);
    ASSERT_EQ(RunLauncher({"--replay", live + "/bus.lcmlog", "--out", out, "--lcm-url",
                           TestBusUrl(47122 + i)},
                          180, &output),
              0)
        << output;
    results[i][0] = ReadText(out + "/trajectory.tum");
    results[i][1] = ReadText(out + "/map.json");
  }
  EXPECT_FALSE(results[0][0].empty());
  EXPECT_FALSE(results[0][1].empty());
  EXPECT_EQ(results[0][0], results[1][0]) << "trajectory.tum differs between two replays";
  EXPECT_EQ(results[0][1], results[1][1]) << "map.json differs between two replays";

  // A live run whose services dropped nothing is reproduced by its replay.
  const std::string metrics = ReadText(live + "/metrics.json");
  if (!RegexSearch(metrics, "\"frames_dropped_total\": 0[,\\s]").empty()) {
    EXPECT_EQ(results[0][0], ReadText(live + "/trajectory.tum"))
        << "the replay does not reproduce the live run's trajectory";
  } else {
    std::cout << "the live run dropped frames: its trajectory is not compared\n";
  }
}

}  // namespace
}  // namespace relplane::testing

namespace relplane::testing {
namespace {

// The full pipeline (simulator, EM segmenter, mapper, logger) meets the mapper's targets on
// straight_hallway, noise-free and with sigma = 1 cm: the scenario's `expect:` section, scored
// by the logger into metrics.json (issue 4 targets; issue 7 integration test).
TEST(Pipeline, StraightHallwayMeetsTheMapperTargets) {
  const char* const noise[] = {"0", "0.01"};
  for (int i = 0; i < 2; ++i) {
    TempDir dir;
    std::string output;
    ASSERT_EQ(
        RunLauncher({Scenario(), "--out", dir.Path() + "/run", "--lcm-url", TestBusUrl(47124 + i),
                     "--set", std::string("sim.sensor.noise_sigma=") + noise[i]},
                    120, &output),
        0)
        << output;
    const std::string metrics = ReadText(dir.Path() + "/run/metrics.json");
    EXPECT_NE(metrics.find("\"expect_pass\": true"), std::string::npos)
        << "noise " << noise[i] << ":\n"
        << output;
  }
}

}  // namespace
}  // namespace relplane::testing
