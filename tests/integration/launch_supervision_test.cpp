// relplane-launch as a real process supervising fake services (shell scripts): a child killed
// under it, a bad scenario, Ctrl-C, and the launcher itself killed. Each test owns a udpm port.

#include <gtest/gtest.h>
#include <signal.h>

#include <thread>

#include "launch_harness.hpp"

namespace relplane::testing {
namespace {

// A scenario file for fake services.
std::string WriteScenario(const std::string& dir, const std::string& services,
                          const std::string& extra = "") {
  const std::string path = dir + "/scenario.yaml";
  WriteText(path, "name: fake\nlaunch:\n  services: " + services +
                      "\n  grace_s: 0.5\n  drain_s: 0.1\n" + extra);
  return path;
}

// A fake service that records its pid in DIR/NAME.pid and then sleeps (exec: same pid).
void WriteSleeper(const std::string& dir, const std::string& name) {
  WriteFakeService(dir, name,
                   "echo $$ > " + dir + "/" + name + ".pid.tmp && mv " + dir + "/" + name +
                       ".pid.tmp " + dir + "/" + name + ".pid\nexec sleep 60");
}

// No process is left with the run's bus in its environment (children, grandchildren), after
// at most `timeout_s` for the kernel to finish them.
void ExpectNoProcessesOn(const std::string& url, double timeout_s) {
  std::vector<pid_t> left;
  for (int i = 0; i < static_cast<int>(timeout_s * 20); ++i) {
    left = ProcessesWithEnvironment("LCM_DEFAULT_URL=" + url);
    if (left.empty()) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ADD_FAILURE() << left.size() << " processes of the run are still alive, e.g. pid " << left[0];
}

TEST(LaunchSupervision, KilledChildIsReportedAndFailsTheRun) {
  TempDir dir;
  const std::string url = TestBusUrl(47111);
  WriteSleeper(dir.Path(), "sim");
  WriteSleeper(dir.Path(), "segmenter");
  Launcher launcher({WriteScenario(dir.Path(), "[sim, segmenter]"), "--bin-dir", dir.Path(),
                     "--out", dir.Path() + "/run", "--lcm-url", url},
                    dir.Path() + "/out.txt");
  const pid_t segmenter = WaitForPidFile(dir.Path() + "/segmenter.pid", 15);
  const pid_t sim = WaitForPidFile(dir.Path() + "/sim.pid", 15);
  ASSERT_GT(segmenter, 0) << launcher.Output();
  ASSERT_GT(sim, 0) << launcher.Output();
  ASSERT_EQ(kill(segmenter, SIGKILL), 0);

  EXPECT_EQ(launcher.Wait(20), 1) << launcher.Output();
  const std::string output = launcher.Output();
  EXPECT_NE(output.find("error: segmenter was killed by signal 9"), std::string::npos) << output;
  EXPECT_NE(output.find("stopped sim"), std::string::npos) << output;
  EXPECT_FALSE(Alive(sim));
  ExpectNoProcessesOn(url, 2.0);
}

TEST(LaunchSupervision, BadScenarioStartsNothing) {
  TempDir dir;
  WriteSleeper(dir.Path(), "sim");
  const std::string run = dir.Path() + "/run";
  const std::string bad = dir.Path() + "/bad.yaml";
  WriteText(bad, "name: bad\nsim: {}\nsimm: {rate_hz: 3}\n");
  std::string output;
  EXPECT_EQ(
      RunLauncher({bad, "--bin-dir", dir.Path(), "--out", run, "--lcm-url", TestBusUrl(47112)}, 20,
                  &output),
      2);
  EXPECT_EQ(output, bad + ":3: key 'simm': unknown top-level key (did you mean 'sim'?)\n");
  EXPECT_FALSE(Exists(run + "/bus.lcmlog"));
  EXPECT_FALSE(Exists(run));
  EXPECT_FALSE(Exists(dir.Path() + "/sim.pid"));

  // A typo in a --set path's section, a missing file, a missing service: same.
  const std::string good = WriteScenario(dir.Path(), "[sim]");
  EXPECT_EQ(RunLauncher({good, "--bin-dir", dir.Path(), "--out", run, "--set", "sym.rate_hz=1"}, 20,
                        &output),
            2);
  EXPECT_EQ(output, "--set 'sym.rate_hz=1': unknown top-level key 'sym' (did you mean 'sim'?)\n");
  EXPECT_EQ(RunLauncher({dir.Path() + "/none.yaml", "--out", run}, 20, &output), 2);
  EXPECT_EQ(output, dir.Path() + "/none.yaml: cannot open the file\n");
  EXPECT_EQ(RunLauncher(
                {WriteScenario(dir.Path(), "[sim, mapper]"), "--bin-dir", dir.Path(), "--out", run},
                20, &output),
            2);
  EXPECT_NE(output.find("relplane-mapper: no such program"), std::string::npos) << output;
  EXPECT_FALSE(Exists(run));
  EXPECT_FALSE(Exists(dir.Path() + "/sim.pid"));
}

TEST(LaunchSupervision, ServiceRefusingTheConfigStartsNothing) {
  TempDir dir;
  WriteSleeper(dir.Path(), "sim");
  // A mapper whose --check-config refuses, as a real service does, with its one line.
  WriteText(dir.Path() + "/relplane-mapper",
            "#!/bin/sh\necho \"$2:7: unknown key 'mapper.bogus'\" >&2\nexit 2\n");
  chmod((dir.Path() + "/relplane-mapper").c_str(), 0755);
  const std::string scenario = WriteScenario(dir.Path(), "[sim, mapper]");
  std::string output;
  EXPECT_EQ(
      RunLauncher({scenario, "--bin-dir", dir.Path(), "--out", dir.Path() + "/run"}, 20, &output),
      2);
  EXPECT_EQ(output, scenario + ":7: unknown key 'mapper.bogus'\n");
  EXPECT_FALSE(Exists(dir.Path() + "/run"));
  EXPECT_FALSE(Exists(dir.Path() + "/sim.pid"));
}

TEST(LaunchSupervision, SimFinishingEndsTheRunCleanly) {
  TempDir dir;
  const std::string url = TestBusUrl(47115);
  WriteFakeService(dir.Path(), "sim", "echo \"hello from $LCM_DEFAULT_URL\"\nsleep 0.3\nexit 0");
  WriteSleeper(dir.Path(), "segmenter");
  const std::string run = dir.Path() + "/run";
  std::string output;
  EXPECT_EQ(
      RunLauncher({"--set", "launch.drain_s=0.2", WriteScenario(dir.Path(), "[sim, segmenter]"),
                   "--bin-dir", dir.Path(), "--out", run, "--lcm-url", url},
                  30, &output),
      0)
      << output;
  EXPECT_FALSE(RegexSearch(output, "\\[sim\\] +hello from " + RegexEscape(url)).empty()) << output;
  EXPECT_NE(output.find("stopped segmenter"), std::string::npos) << output;
  EXPECT_NE(output.find("stopped lcm-logger"), std::string::npos) << output;
  EXPECT_TRUE(Exists(run + "/bus.lcmlog"));
  // The services got the scenario with the override applied.
  EXPECT_NE(ReadText(run + "/scenario.yaml").find("drain_s: 0.2"), std::string::npos);
  ExpectNoProcessesOn(url, 2.0);
}

// The logger writes its files when stopped: failing then fails the run.
TEST(LaunchSupervision, FailureWhileStoppingFailsTheRun) {
  TempDir dir;
  const std::string url = TestBusUrl(47118);
  WriteFakeService(dir.Path(), "sim", "sleep 0.3\nexit 0");
  WriteFakeService(dir.Path(), "logger",
                   "trap 'echo cannot write map.json >&2; exit 1' INT\n"
                   "while true; do sleep 0.1; done");
  std::string output;
  EXPECT_EQ(RunLauncher({WriteScenario(dir.Path(), "[sim, logger]"), "--bin-dir", dir.Path(),
                         "--out", dir.Path() + "/run", "--lcm-url", url},
                        30, &output),
            1)
      << output;
  EXPECT_FALSE(RegexSearch(output, "\\[logger\\] +cannot write map.json").empty()) << output;
  EXPECT_NE(output.find("error: logger exited with code 1 while stopping"), std::string::npos)
      << output;
  EXPECT_NE(output.find("stopped lcm-logger"), std::string::npos) << output;
  ExpectNoProcessesOn(url, 2.0);
}

TEST(LaunchSupervision, InterruptStopsEverythingWithoutOrphans) {
  TempDir dir;
  const std::string url = TestBusUrl(47113);
  const std::string d = dir.Path();
  WriteSleeper(d, "sim");
  // A segmenter with a grandchild, and a mapper that ignores SIGINT (needs SIGTERM).
  WriteFakeService(
      d, "segmenter",
      "sleep 60 &\necho $! > " + d + "/grandchild.pid\necho $$ > " + d + "/segmenter.pid\nwait");
  WriteFakeService(d, "mapper",
                   "trap '' INT\necho $$ > " + d + "/mapper.pid\nwhile true; do sleep 0.1; done");
  Launcher launcher({WriteScenario(d, "[sim, segmenter, mapper]"), "--bin-dir", d, "--out",
                     d + "/run", "--lcm-url", url},
                    d + "/out.txt");
  std::vector<pid_t> pids;
  for (const char* name : {"sim", "segmenter", "grandchild", "mapper"}) {
    pids.push_back(WaitForPidFile(d + "/" + name + ".pid", 20));
    ASSERT_GT(pids.back(), 0) << name << "\n" << launcher.Output();
  }
  ASSERT_EQ(kill(launcher.Pid(), SIGINT), 0);

  EXPECT_EQ(launcher.Wait(20), 130) << launcher.Output();
  const std::string output = launcher.Output();
  EXPECT_NE(output.find("interrupted"), std::string::npos) << output;
  EXPECT_NE(output.find("stopped segmenter"), std::string::npos) << output;
  EXPECT_NE(output.find("sending SIGTERM"), std::string::npos) << output;
  EXPECT_TRUE(Exists(d + "/run/bus.lcmlog"));
  for (pid_t pid : pids) EXPECT_FALSE(Alive(pid)) << pid;
  ExpectNoProcessesOn(url, 2.0);
}

TEST(LaunchSupervision, KilledLauncherTakesItsChildrenAlong) {
  TempDir dir;
  const std::string url = TestBusUrl(47114);
  WriteSleeper(dir.Path(), "sim");
  WriteSleeper(dir.Path(), "segmenter");
  Launcher launcher({WriteScenario(dir.Path(), "[sim, segmenter]"), "--bin-dir", dir.Path(),
                     "--out", dir.Path() + "/run", "--lcm-url", url},
                    dir.Path() + "/out.txt");
  const pid_t sim = WaitForPidFile(dir.Path() + "/sim.pid", 20);
  ASSERT_GT(sim, 0) << launcher.Output();
  ASSERT_FALSE(ProcessesWithEnvironment("LCM_DEFAULT_URL=" + url).empty());
  ASSERT_EQ(kill(launcher.Pid(), SIGKILL), 0);
  EXPECT_EQ(launcher.Wait(10), 128 + SIGKILL);
  ExpectNoProcessesOn(url, 3.0);  // PR_SET_PDEATHSIG: the kernel kills them
}

}  // namespace
}  // namespace relplane::testing
