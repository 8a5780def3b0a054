// A 640x480 cloud (~3.7 MB, ~57 UDP fragments) on a bus URL without recv_buf_size reaches the
// real segmenter: it asks for a receive buffer big enough itself (bus::CloudBusUrl). With LCM's
// default buffer no such cloud arrives whole. Port 47173.

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <relplane/plane_set_t.hpp>
#include <relplane/point_cloud_t.hpp>
#include <relplane/status_t.hpp>
#include <set>
#include <string>
#include <thread>

#include "relplane/common/bus.hpp"

extern char** environ;

namespace relplane {
namespace {

// A wall 3 m ahead seen by a 640x480 depth camera (sensor frame: x forward, y left, z up).
point_cloud_t VgaWall(int64_t seq) {
  point_cloud_t cloud{};
  cloud.seq = seq;
  cloud.utime = 1000000 + seq * 33333;
  cloud.num_points = 640 * 480;
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 640; ++u) {
      cloud.x.push_back(3.0f);
      cloud.y.push_back(2.0f * (320 - u) / 320.0f);
      cloud.z.push_back(1.5f * (240 - v) / 240.0f);
    }
  }
  return cloud;
}

// Runs `argv` until the object dies.
class Process {
 public:
  explicit Process(std::vector<std::string> argv) {
    std::vector<char*> raw;
    for (std::string& a : argv) raw.push_back(a.data());
    raw.push_back(nullptr);
    if (posix_spawn(&pid_, raw[0], nullptr, nullptr, raw.data(), environ) != 0) pid_ = -1;
  }
  ~Process() {
    if (pid_ <= 0) return;
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  bool Started() const { return pid_ > 0; }

 private:
  pid_t pid_ = -1;
};

TEST(LargeClouds, VgaCloudsOnAUrlWithoutReceiveBufferAreProcessed) {
  const std::string url = "udpm://239.255.76.67:47173?ttl=0";
  Process segmenter({RELPLANE_SEGMENTER_PATH, "--lcm-url", url, "--log-level", "warn"});
  ASSERT_TRUE(segmenter.Started());

  auto bus = bus::OpenLcmBus(url);
  bool listening = false;
  std::set<int64_t> processed;
  const auto ignore = [](const std::string&) {};
  bus::Subscribe<status_t>(
      *bus, "STATUS",
      [&](const status_t& m) { listening = listening || m.service == "relplane-segmenter"; },
      ignore);
  bus::Subscribe<plane_set_t>(
      *bus, "PLANES", [&](const plane_set_t& m) { processed.insert(m.seq); }, ignore);
  const auto pump_until = [&](double seconds, const std::function<bool()>& done) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (!done() && std::chrono::steady_clock::now() < end) bus->Handle(50);
    return done();
  };
  // STATUS comes once a second from the segmenter's loop, which runs once it subscribed.
  ASSERT_TRUE(pump_until(20, [&] { return listening; })) << "no STATUS from the segmenter";

  for (int64_t seq = 0; seq < 3; ++seq) {
    ASSERT_TRUE(bus::Publish(*bus, "SENSOR_POINTS", VgaWall(seq)));
    EXPECT_TRUE(pump_until(20, [&] { return processed.count(seq) > 0; }))
        << "cloud " << seq << " of 640x480 points was not processed";
  }
}

}  // namespace
}  // namespace relplane
