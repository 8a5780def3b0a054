// Clouds on a bus of their own (issue 54): with --cloud-url the pipeline runs, the main bus
// (where the mapper and the logger listen) never carries SENSOR_POINTS, the mapper has no
// socket on the cloud port, bus.lcmlog still holds every channel, and its replay (clouds played
// onto the cloud bus) reproduces the live trajectory. Ports 47160-47163.

#include <dirent.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <map>
#include <set>
#include <sstream>

#include "launch_harness.hpp"
#include "log_counts.hpp"
#include "relplane/common/bus.hpp"

namespace relplane::testing {
namespace {

std::string Scenario() { return SourceDir() + "/scenarios/straight_hallway.yaml"; }

// The local UDP ports of the sockets process `pid` holds (its socket inodes looked up in
// /proc/net/udp).
std::set<int> UdpPortsOf(pid_t pid) {
  std::set<std::string> inodes;
  const std::string fd_dir = "/proc/" + std::to_string(pid) + "/fd";
  if (DIR* dir = opendir(fd_dir.c_str())) {
    while (dirent* e = readdir(dir)) {
      char target[256];
      const ssize_t n = readlink((fd_dir + "/" + e->d_name).c_str(), target, sizeof target - 1);
      const std::string link(target, n > 0 ? n : 0);
      if (link.rfind("socket:[", 0) == 0) inodes.insert(link.substr(8, link.size() - 9));
    }
    closedir(dir);
  }
  std::set<int> ports;
  std::istringstream lines(ReadText("/proc/net/udp"));
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream f(line);
    std::string slot, local, remote, state, queues, timer, retr, uid, timeout, inode;
    if (!(f >> slot >> local >> remote >> state >> queues >> timer >> retr >> uid >> timeout >>
          inode) ||
        inodes.count(inode) == 0) {
      continue;
    }
    ports.insert(std::stoi(local.substr(local.find(':') + 1), nullptr, 16));
  }
  return ports;
}

// The live relplane-mapper of the run on `url`, -1 when there is none.
pid_t FindMapper(const std::string& url) {
  for (pid_t pid : ProcessesWithEnvironment("LCM_DEFAULT_URL=" + url)) {
    char exe[4096];
    const ssize_t n = readlink(("/proc/" + std::to_string(pid) + "/exe").c_str(), exe, sizeof exe);
    const std::string path(exe, n > 0 ? n : 0);
    if (path.size() > 16 && path.compare(path.size() - 16, 16, "/relplane-mapper") == 0) {
      return pid;
    }
  }
  return -1;
}

TEST(CloudBus, MapperNeverReceivesCloudsAndTheReplayGivesTheSameTrajectory) {
  TempDir dir;
  const std::string live = dir.Path() + "/live";
  const std::string url = TestBusUrl(47160), cloud_url = TestBusUrl(47161);
  Launcher launcher(
      {Scenario(), "--out", live, "--lcm-url", url, "--cloud-url", cloud_url, "--iterations", "90"},
      dir.Path() + "/live.txt");
  // Listeners on both buses, opened after the launcher started so that its children do not
  // inherit their sockets: a socket on the main port receives whatever the mapper's does.
  auto main_bus = bus::OpenLcmBus(url);
  auto cloud_bus = bus::OpenLcmBus(cloud_url);
  int clouds_on_main = 0, poses_on_main = 0, clouds_on_cloud_bus = 0, poses_on_cloud_bus = 0;
  auto count = [](int* n) { return [n](const std::string&, const uint8_t*, size_t) { ++*n; }; };
  main_bus->SubscribeRaw("SENSOR_POINTS", count(&clouds_on_main), 1000);
  main_bus->SubscribeRaw("POSE", count(&poses_on_main), 1000);
  cloud_bus->SubscribeRaw("SENSOR_POINTS", count(&clouds_on_cloud_bus), 1000);
  cloud_bus->SubscribeRaw("POSE", count(&poses_on_cloud_bus), 1000);
  int code = -1;
  std::set<int> mapper_ports;
  for (int round = 0; round < 6000 && code < 0; ++round) {
    main_bus->Handle(5);
    cloud_bus->Handle(5);
    if (mapper_ports.empty()) {
      if (const pid_t mapper = FindMapper(url); mapper > 0) mapper_ports = UdpPortsOf(mapper);
    }
    code = launcher.Wait(0);
  }
  while (main_bus->Handle(50) > 0 || cloud_bus->Handle(50) > 0) {
  }
  ASSERT_EQ(code, 0) << launcher.Output();
  EXPECT_EQ(clouds_on_main, 0) << "SENSOR_POINTS reached the main bus";
  EXPECT_GT(poses_on_main, 0);
  EXPECT_GT(clouds_on_cloud_bus, 0);
  EXPECT_EQ(poses_on_cloud_bus, 0);
  EXPECT_EQ(mapper_ports.count(47161), 0u) << "the mapper has a socket on the cloud port";
  EXPECT_EQ(mapper_ports.count(47160), 1u) << "the mapper was not seen on the main port";

  // One log with every channel; the cloud recorder's part was merged into it.
  const std::map<std::string, int> counts = ChannelCounts(live + "/bus.lcmlog");
  EXPECT_EQ(CountOf(counts, "SENSOR_POINTS"), 90);
  EXPECT_EQ(CountOf(counts, "SIM_TRUTH"), 90);
  EXPECT_GT(CountOf(counts, "POSE"), 0);
  EXPECT_FALSE(Exists(live + "/clouds.lcmlog"));

  // The replay plays the clouds onto a cloud bus of its own, the truth onto the main bus.
  const std::string replay = dir.Path() + "/replay";
  std::string output;
  ASSERT_EQ(RunLauncher({"--replay", live + "/bus.lcmlog", "--out", replay, "--lcm-url",
                         TestBusUrl(47162), "--cloud-url", TestBusUrl(47163)},
                        120, &output),
            0)
      << output;
  EXPECT_NE(output.find("clouds (SENSOR_POINTS) on " + TestBusUrl(47163)), std::string::npos)
      << output;
  const std::string metrics = ReadText(live + "/metrics.json");
  if (!RegexSearch(metrics, "\"frames_dropped_total\": 0[,\\s]").empty()) {
    EXPECT_EQ(ReadText(replay + "/trajectory.tum"), ReadText(live + "/trajectory.tum"))
        << "the replay does not reproduce the live run's trajectory";
  } else {
    std::cout << "the live run dropped frames: its trajectory is not compared\n";
    EXPECT_FALSE(ReadText(replay + "/trajectory.tum").empty());
  }
}

}  // namespace
}  // namespace relplane::testing
