// The mapper killed with SIGKILL mid-run (issue 8): the launcher's restart policy starts it
// again, it replays its checkpoint journal (RUN/mapper.journal) and goes on with the map it had.
// The final map has no duplicate walls and the ATE is within twice an undisturbed run's.
// Ports 47155-47156.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "launch_harness.hpp"

namespace relplane::testing {
namespace {

const std::vector<std::string> kArgs = {SourceDir() + "/scenarios/straight_hallway.yaml", "--set",
                                        "sim.sensor.noise_sigma=0.01", "--set",
                                        "launch.restart={max_restarts: 1, services: [mapper]}"};

double Ate(const std::string& metrics) {
  const std::vector<std::string> match = RegexSearch(metrics, "\"ate_rmse_m\": ([-+0-9.eE]+)");
  return match.empty() ? -1 : std::stod(match[1]);
}

long FileSize(const std::string& path) {
  struct stat st {};
  return stat(path.c_str(), &st) == 0 ? static_cast<long>(st.st_size) : -1;
}

// The live relplane-mapper process on `url` (its environment holds the bus), or -1.
pid_t FindMapper(const std::string& url) {
  for (pid_t pid : ProcessesWithEnvironment("LCM_DEFAULT_URL=" + url)) {
    char exe[4096];
    const ssize_t n = readlink(("/proc/" + std::to_string(pid) + "/exe").c_str(), exe, sizeof exe);
    const std::string path(exe, n > 0 ? static_cast<size_t>(n) : 0);
    if (path.size() >= 16 && path.compare(path.size() - 16, 16, "/relplane-mapper") == 0) {
      return pid;
    }
  }
  return -1;
}

TEST(MapperResume, KilledMapperResumesFromItsJournal) {
  TempDir dir;
  std::string output;
  std::vector<std::string> args = kArgs;
  args.insert(args.end(), {"--out", dir.Path() + "/calm", "--lcm-url", TestBusUrl(47156)});
  ASSERT_EQ(RunLauncher(args, 120, &output), 0) << output;
  const double calm_ate = Ate(ReadText(dir.Path() + "/calm/metrics.json"));
  ASSERT_GE(calm_ate, 0.0);

  const std::string run = dir.Path() + "/killed";
  const std::string url = TestBusUrl(47155);
  args = kArgs;
  args.insert(args.end(), {"--out", run, "--lcm-url", url});
  Launcher launcher(args, dir.Path() + "/out.txt");
  // Kill it once 40 KB of plane sets are in its journal (about 25 of the 151 frames).
  for (int i = 0; i < 600 && FileSize(run + "/mapper.journal") < 40000; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const pid_t mapper = FindMapper(url);
  ASSERT_GT(mapper, 0) << launcher.Output();
  ASSERT_EQ(kill(mapper, SIGKILL), 0);

  ASSERT_EQ(launcher.Wait(120), 0) << launcher.Output();
  const std::string out = launcher.Output();
  EXPECT_NE(out.find("[launch] restarts: mapper 1"), std::string::npos) << out;
  const std::vector<std::string> restored = RegexSearch(out, "resumed from .*: (\\d+) iterations");
  ASSERT_FALSE(restored.empty()) << out;
  EXPECT_GE(std::stol(restored[1]), 20) << out;

  const std::string metrics = ReadText(run + "/metrics.json");
  EXPECT_NE(metrics.find("\"duplicates\": 0"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"lost\": 0"), std::string::npos) << metrics;
  const double ate = Ate(metrics);
  ASSERT_GE(ate, 0.0) << metrics;
  EXPECT_LE(ate, 2.0 * calm_ate) << "undisturbed " << calm_ate << "\n" << out;
}

}  // namespace
}  // namespace relplane::testing
