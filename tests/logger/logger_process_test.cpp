// relplane-logger as a real process on a udpm bus of its own (ports 47140-47149): fed
// hand-made messages, killed with SIGKILL or stopped with SIGINT, its run folder must parse.
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include "fixtures.hpp"
#include "messages.hpp"
#include "process.hpp"
#include "relplane/common/bus.hpp"
#include "run_folder_check.hpp"

namespace relplane::testing {
namespace {

namespace fs = std::filesystem;

std::string Url(int port) { return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0"; }

void Sleep(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

// Publishes the room, `n` truth/planes/pose triples (estimate 5 cm off in x), maps and a STATUS.
void PublishRun(bus::Bus& bus, int n) {
  bus::Publish(bus, "SIM_WORLD", MapMessage(Room()));
  const std::vector<eval::PoseSample> truth = LoopInRoom();
  eval::MapSnapshot map;
  map.planes = Room().planes;
  map.groups = {{0, 0, {0, 1}}, {1, 2, {1, 2, 3}}};
  for (int i = 0; i < n; ++i) {
    eval::PoseSample estimate = truth[i];
    estimate.position.x() += 0.05;
    bus::Publish(bus, "SIM_TRUTH", PoseMessage(truth[i]));
    bus::Publish(bus, "PLANES", PlanesMessage(truth[i].seq));
    bus::Publish(bus, "POSE", PoseMessage(estimate));
    if (i % 10 == 0) bus::Publish(bus, "MAP", MapMessage(map));
    Sleep(0.005);
  }
  bus::Publish(bus, "STATUS", StatusMessage("relplane-mapper", n, 4.0f));
}

TEST(LoggerProcess, SigkilledLoggerLeavesCompleteFilesAtMostASecondOld) {
  const ScratchDir scratch("relplane-logger-sigkill");
  const std::string dir = scratch / "run";
  const std::string url = Url(47140);
  Process logger({RELPLANE_LOGGER_PATH, "--out", dir, "--lcm-url", url, "--log-level", "warn"},
                 dir + ".out", dir + ".err");
  // The logger subscribes before its first write, so once a file exists it hears everything.
  ASSERT_TRUE(WaitForFile(dir + "/metrics.json", 10.0));
  std::unique_ptr<bus::Bus> bus = bus::OpenLcmBus(url);
  PublishRun(*bus, 40);
  // Two flush periods: the data, then the logger's first own STATUS (a new row) are written.
  Sleep(2.5);
  // Nothing new arrives (only STATUS with unchanged counters): the folder is left alone.
  const auto written = fs::last_write_time(dir + "/metrics.json");
  Sleep(1.5);
  EXPECT_EQ(fs::last_write_time(dir + "/metrics.json"), written);
  logger.Signal(SIGKILL);
  EXPECT_EQ(logger.Wait(10.0), 128 + SIGKILL);

  const RunFolder folder = CheckRunFolder(dir);
  EXPECT_EQ(folder.trajectory.size(), 40u);
  EXPECT_EQ(folder.truth.size(), 40u);
  EXPECT_EQ(folder.map["planes"].items.size(), 5u);
  EXPECT_EQ(folder.map["groups"].items.size(), 2u);
  EXPECT_EQ(folder.metrics["source"].text, "relplane-logger");
  EXPECT_EQ(folder.metrics["run"]["iterations"].number, 40);
  EXPECT_NEAR(folder.metrics["trajectory"]["ate_rmse_m"].number, 0.05, 1e-6);
  EXPECT_EQ(folder.metrics["map"]["walls_mapped"].number, 4);
  EXPECT_EQ(folder.metrics["timing"]["end_to_end"]["samples"].number, 40);
  EXPECT_EQ(folder.metrics["timing"]["services"]["relplane-mapper"]["frames_dropped"].number, 2);
}

TEST(LoggerProcess, InterruptWritesFinalFilesAndASummaryWithExpectations) {
  const ScratchDir scratch("relplane-logger-sigint");
  const std::string dir = scratch / "run";
  const std::string url = Url(47141);
  const std::string scenario = scratch / "scenario.yaml";
  WriteFileForTest(scenario,
                   "name: t\nlogger: {flush_period_s: 5}\n"
                   "expect: {ate_rmse_max_m: 0.01, iterations_min: 20}\n");
  Process logger({RELPLANE_LOGGER_PATH, "--out", dir, "--lcm-url", url, "--config", scenario,
                  "--log-level", "warn"},
                 dir + ".out", dir + ".err");
  ASSERT_TRUE(WaitForFile(dir + "/metrics.json", 10.0));
  std::unique_ptr<bus::Bus> bus = bus::OpenLcmBus(url);
  PublishRun(*bus, 20);
  Sleep(0.3);  // delivered, but well before the 5 s flush period: only the exit writes them
  logger.Signal(SIGINT);
  EXPECT_EQ(logger.Wait(10.0), 0);  // scores are reported, not enforced

  const RunFolder folder = CheckRunFolder(dir);
  EXPECT_EQ(folder.trajectory.size(), 20u);
  EXPECT_FALSE(folder.metrics["expect_pass"].boolean);
  EXPECT_EQ(folder.metrics["expect"][0]["key"].text, "iterations_min");
  EXPECT_TRUE(folder.metrics["expect"][0]["pass"].boolean);
  EXPECT_FALSE(folder.metrics["expect"][1]["pass"].boolean);
  std::string summary;
  ASSERT_TRUE(eval::ReadFile(dir + ".out", &summary));
  EXPECT_NE(summary.find("ATE RMSE       0.050 m"), std::string::npos) << summary;
  EXPECT_NE(summary.find("iterations_min"), std::string::npos) << summary;
  EXPECT_NE(summary.find("PASS"), std::string::npos) << summary;
  EXPECT_NE(summary.find("FAIL"), std::string::npos) << summary;
}

TEST(LoggerProcess, CheckConfigRefusesAnUnknownExpectKeyInOneLine) {
  const ScratchDir scratch("relplane-logger-check");
  const std::string scenario = scratch / "scenario.yaml";
  WriteFileForTest(scenario, "name: t\nexpect:\n  ate_rsme_max_m: 0.05\n");
  std::string out, err;
  EXPECT_EQ(
      RunProcess({RELPLANE_LOGGER_PATH, "--config", scenario, "--check-config"}, 10.0, &out, &err),
      2);
  EXPECT_NE(err.find(":3: unknown key 'expect.ate_rsme_max_m'"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  WriteFileForTest(scenario, "name: t\nsim: {x: 1}\nlogger: {flush_period_s: 0.5}\n");
  EXPECT_EQ(
      RunProcess({RELPLANE_LOGGER_PATH, "--config", scenario, "--check-config"}, 10.0, &out, &err),
      0)
      << err;
}

}  // namespace
}  // namespace relplane::testing

// As root, run in a private network namespace with a multicast route on lo, so two copies of
// this test (two build trees) never hear each other even on the same port; otherwise use the
// host's network and rely on the port being unique.
int main(int argc, char** argv) {
  if (geteuid() == 0 && unshare(CLONE_NEWNET) == 0) {
    if (std::system("ip link set lo up && ip route add 224.0.0.0/4 dev lo") != 0) {
      std::fprintf(stderr, "logger_process_test: no multicast route in the private namespace\n");
      return 1;
    }
  }
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
