// Anything on the bus can send anything (issue 7, issue 8): the real pipeline keeps running
// while random bytes, and random bytes behind each type's true fingerprint, arrive on every
// relplane channel. The run must end normally and the rejections must be counted and said.

#include <gtest/gtest.h>
#include <relplane/map_t.hpp>
#include <relplane/odometry_t.hpp>
#include <relplane/plane_set_t.hpp>
#include <relplane/point_cloud_t.hpp>
#include <relplane/pose_t.hpp>
#include <relplane/status_t.hpp>

#include <chrono>
#include <random>
#include <thread>

#include "launch_harness.hpp"
#include "relplane/common/bus.hpp"

namespace relplane::testing {
namespace {

// Random bytes, half of the time behind the fingerprint of `M` so they reach its decoder.
template <class M>
std::vector<uint8_t> Junk(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> size(0, 2000), byte(0, 255), coin(0, 1);
  std::vector<uint8_t> bytes;
  if (coin(rng) == 1) {
    const int64_t hash = M::getHash();
    for (int i = 7; i >= 0; --i) bytes.push_back(static_cast<uint8_t>(hash >> (8 * i)));
  }
  const int n = size(rng);
  for (int i = 0; i < n; ++i) bytes.push_back(static_cast<uint8_t>(byte(rng)));
  return bytes;
}

TEST(HostileBus, ServicesKeepRunningOnRandomBytes) {
  TempDir dir;
  const std::string url = TestBusUrl(47129);  // 47122-47123: the pipeline replays
  Launcher launcher({SourceDir() + "/scenarios/straight_hallway.yaml", "--out",
                     dir.Path() + "/run", "--lcm-url", url, "--iterations", "120", "--set",
                     "launch.services=[sim, segmenter, mapper, logger]"},
                    dir.Path() + "/out.txt");
  auto bus = bus::OpenLcmBus(url);
  std::mt19937_64 rng(11);
  // About three seconds of junk, 20 messages per channel per second, while the run goes on.
  for (int round = 0; round < 60; ++round) {
    const std::vector<std::pair<std::string, std::vector<uint8_t>>> junk = {
        {"SENSOR_POINTS", Junk<point_cloud_t>(rng)}, {"PLANES", Junk<plane_set_t>(rng)},
        {"POSE", Junk<pose_t>(rng)},                 {"MAP", Junk<map_t>(rng)},
        {"SIM_TRUTH", Junk<pose_t>(rng)},            {"SIM_WORLD", Junk<map_t>(rng)},
        {"STATUS", Junk<status_t>(rng)},            {"ODOMETRY", Junk<odometry_t>(rng)}};
    for (const auto& [channel, bytes] : junk) bus->PublishRaw(channel, bytes.data(), bytes.size());
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_EQ(launcher.Wait(120), 0) << launcher.Output();
  const std::string out = launcher.Output();
  // Each stage said it rejected input, and the run's files are complete.
  for (const char* service : {"[segmenter]", "[mapper]"}) {
    bool said = false;
    std::istringstream lines(out);
    for (std::string line; std::getline(lines, line);) {
      said = said || (line.find(service) != std::string::npos &&
                      line.find("reject") != std::string::npos);
    }
    EXPECT_TRUE(said) << service << " did not report rejections:\n" << out;
  }
  EXPECT_TRUE(Exists(dir.Path() + "/run/trajectory.tum")) << out;
  EXPECT_TRUE(Exists(dir.Path() + "/run/metrics.json")) << out;
}

}  // namespace
}  // namespace relplane::testing
