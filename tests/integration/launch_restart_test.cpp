// The launcher's restart policy (launch.restart) with fake services (shell scripts): a service
// killed with SIGKILL comes back with the same command line and the run ends 0; past
// max_restarts the run fails as without a policy. Ports 47150-47151.

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <sstream>
#include <thread>

#include "launch_harness.hpp"

namespace relplane::testing {
namespace {

// sim: runs until DIR/finish exists, then ends the run normally. mapper: appends its pid and
// its arguments to DIR/mapper.starts (one line per start), then sleeps.
void WriteServices(const std::string& dir) {
  WriteFakeService(dir, "sim", "while [ ! -f " + dir + "/finish ]; do sleep 0.05; done\nexit 0");
  WriteFakeService(dir, "mapper", "echo \"$$ $*\" >> " + dir + "/mapper.starts\nexec sleep 60");
}

std::string WriteScenario(const std::string& dir, int max_restarts) {
  const std::string path = dir + "/scenario.yaml";
  WriteText(path,
            "name: restart\nlaunch:\n  services: [sim, mapper]\n  grace_s: 0.5\n"
            "  drain_s: 0.1\n  restart: {max_restarts: " +
                std::to_string(max_restarts) + ", services: [mapper]}\n");
  return path;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Waits until DIR/mapper.starts has `n` lines; returns the pid on the last one (-1: time-out).
pid_t WaitForStart(const std::string& dir, size_t n, double timeout_s) {
  for (int i = 0; i < static_cast<int>(timeout_s * 20); ++i) {
    const std::vector<std::string> lines = Exists(dir + "/mapper.starts")
                                               ? Lines(ReadText(dir + "/mapper.starts"))
                                               : std::vector<std::string>{};
    if (lines.size() >= n) return static_cast<pid_t>(std::stol(lines[n - 1]));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return -1;
}

// The arguments of a start line (after the pid).
std::string Arguments(const std::string& line) { return line.substr(line.find(' ') + 1); }

TEST(LaunchRestart, KilledServiceComesBackAndTheRunEndsWell) {
  TempDir dir;
  WriteServices(dir.Path());
  Launcher launcher({WriteScenario(dir.Path(), 2), "--bin-dir", dir.Path(), "--out",
                     dir.Path() + "/run", "--lcm-url", TestBusUrl(47150)},
                    dir.Path() + "/out.txt");
  for (size_t start = 1; start <= 2; ++start) {  // two kills: both within the limit
    const pid_t mapper = WaitForStart(dir.Path(), start, 15);
    ASSERT_GT(mapper, 0) << launcher.Output();
    ASSERT_EQ(kill(mapper, SIGKILL), 0);
  }
  const pid_t third = WaitForStart(dir.Path(), 3, 15);
  ASSERT_GT(third, 0) << launcher.Output();
  EXPECT_TRUE(Alive(third));
  WriteText(dir.Path() + "/finish", "");

  EXPECT_EQ(launcher.Wait(20), 0) << launcher.Output();
  const std::string out = launcher.Output();
  EXPECT_NE(out.find("mapper was killed by signal 9 (Killed); restarting it (restart 1 of 2)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("restarting it (restart 2 of 2)"), std::string::npos) << out;
  EXPECT_NE(out.find("[launch] restarts: mapper 2"), std::string::npos) << out;
  EXPECT_NE(out.find("stopped mapper"), std::string::npos) << out;
  // Every start had the same command line.
  const std::vector<std::string> starts = Lines(ReadText(dir.Path() + "/mapper.starts"));
  ASSERT_EQ(starts.size(), 3u);
  EXPECT_EQ(Arguments(starts[1]), Arguments(starts[0]));
  EXPECT_EQ(Arguments(starts[2]), Arguments(starts[0]));
  EXPECT_FALSE(Alive(third));
}

TEST(LaunchRestart, CrashBeyondTheLimitFailsTheRun) {
  TempDir dir;
  WriteServices(dir.Path());
  Launcher launcher({WriteScenario(dir.Path(), 1), "--bin-dir", dir.Path(), "--out",
                     dir.Path() + "/run", "--lcm-url", TestBusUrl(47151)},
                    dir.Path() + "/out.txt");
  for (size_t start = 1; start <= 2; ++start) {
    const pid_t mapper = WaitForStart(dir.Path(), start, 15);
    ASSERT_GT(mapper, 0) << launcher.Output();
    ASSERT_EQ(kill(mapper, SIGKILL), 0);
  }
  EXPECT_EQ(launcher.Wait(20), 1) << launcher.Output();
  const std::string out = launcher.Output();
  EXPECT_NE(out.find("restarting it (restart 1 of 1)"), std::string::npos) << out;
  EXPECT_NE(out.find("mapper was killed by signal 9 (Killed) after 1 restarts "
                     "(launch.restart.max_restarts): giving up"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("[launch] restarts: mapper 1"), std::string::npos) << out;
  EXPECT_EQ(Lines(ReadText(dir.Path() + "/mapper.starts")).size(), 2u);
}

}  // namespace
}  // namespace relplane::testing
