// Issue 2 item 9: relplane-launch runs relplane-sim and lcm-logger on a bus of their own; the
// recorded bus.lcmlog holds one SENSOR_POINTS and one SIM_TRUTH per iteration, and every point,
// moved into the world with the SIM_TRUTH of its seq, lies on a true rectangle of SIM_WORLD
// within the range noise.

#include <gtest/gtest.h>
#include <lcm/eventlog.h>
#include <sys/stat.h>

#include <Eigen/Geometry>
#include <iostream>
#include <map>
#include <relplane/map_t.hpp>
#include <relplane/odometry_t.hpp>
#include <relplane/point_cloud_t.hpp>
#include <relplane/pose_t.hpp>

#include "launch_harness.hpp"

namespace relplane::testing {
namespace {

constexpr int kIterations = 30;
constexpr double kSigma = 0.01;  // range noise, metres (sim.sensor.noise_sigma)

struct Recording {
  std::map<int64_t, point_cloud_t> clouds;  // by seq
  std::map<int64_t, pose_t> truth;
  std::vector<map_t> worlds;
  int cloud_events = 0;
  int truth_events = 0;
  int odometry_events = 0;
  std::vector<odometry_t> odometry;
  int other_events = 0;
};

template <class M>
M Decode(const lcm_eventlog_event_t& event) {
  M message;
  EXPECT_EQ(message.decode(event.data, 0, event.datalen), event.datalen) << event.channel;
  return message;
}

Recording ReadLog(const std::string& path) {
  Recording r;
  lcm_eventlog_t* log = lcm_eventlog_create(path.c_str(), "r");
  if (!log) {
    ADD_FAILURE() << "cannot open " << path;
    return r;
  }
  while (lcm_eventlog_event_t* event = lcm_eventlog_read_next_event(log)) {
    const std::string channel = event->channel;
    if (channel == "SENSOR_POINTS") {
      const auto cloud = Decode<point_cloud_t>(*event);
      r.clouds[cloud.seq] = cloud;
      ++r.cloud_events;
    } else if (channel == "SIM_TRUTH") {
      const auto pose = Decode<pose_t>(*event);
      r.truth[pose.seq] = pose;
      ++r.truth_events;
    } else if (channel == "ODOMETRY") {
      r.odometry.push_back(Decode<odometry_t>(*event));
      ++r.odometry_events;
    } else if (channel == "SIM_WORLD") {
      r.worlds.push_back(Decode<map_t>(*event));
    } else {
      ++r.other_events;
    }
    lcm_eventlog_free_event(event);
  }
  lcm_eventlog_destroy(log);
  return r;
}

// A true rectangle: plane and the two edge vectors from its first corner.
struct Rectangle {
  Eigen::Vector3d normal, corner, u, v;
  double d;
  bool wall;
};

std::vector<Rectangle> Rectangles(const map_t& world) {
  std::vector<Rectangle> out;
  for (const plane_t& p : world.planes) {
    EXPECT_EQ(p.num_vertices, 4);
    if (p.num_vertices != 4) continue;
    const auto vertex = [&](int i) {
      return Eigen::Vector3d(p.vertices[i][0], p.vertices[i][1], p.vertices[i][2]);
    };
    Rectangle r;
    r.normal = Eigen::Vector3d(p.normal[0], p.normal[1], p.normal[2]);
    r.d = p.d;
    r.corner = vertex(0);
    r.u = vertex(1) - vertex(0);
    r.v = vertex(3) - vertex(0);
    r.wall = std::abs(r.normal.z()) < 0.1;
    out.push_back(r);
  }
  return out;
}

// Distance from `p` to the nearest rectangle whose extent (grown by `margin`) holds its
// projection; `*on_wall` tells whether that one is a wall. Infinity when none does.
double DistanceToWorld(const std::vector<Rectangle>& world, const Eigen::Vector3d& p, double margin,
                       bool* on_wall) {
  double best = std::numeric_limits<double>::infinity();
  for (const Rectangle& r : world) {
    const Eigen::Vector3d q = p - r.corner;
    const double s = q.dot(r.u) / r.u.squaredNorm();
    const double t = q.dot(r.v) / r.v.squaredNorm();
    const double su = margin / r.u.norm(), tv = margin / r.v.norm();
    if (s < -su || s > 1 + su || t < -tv || t > 1 + tv) continue;
    const double distance = std::abs(r.normal.dot(p) + r.d);
    if (distance < best) {
      best = distance;
      *on_wall = r.wall;
    }
  }
  return best;
}

TEST(SimRecording, OneCloudAndTruthPerIterationOnTheTrueWalls) {
  const std::string scenario = SourceDir() + "/scenarios/straight_hallway.yaml";
  ASSERT_TRUE(Exists(scenario)) << scenario << " is missing";
  TempDir dir;
  const std::string run = dir.Path() + "/run";
  std::string output;
  ASSERT_EQ(RunLauncher({scenario, "--out", run, "--lcm-url", TestBusUrl(47110), "--set",
                         "launch.services=[sim]", "--set",
                         "sim.sensor.noise_sigma=" + std::to_string(kSigma), "--set",
                         "launch.rate_hz=60", "--iterations", std::to_string(kIterations)},
                        120, &output),
            0)
      << output;

  const Recording r = ReadLog(run + "/bus.lcmlog");
  EXPECT_EQ(r.cloud_events, kIterations) << output;
  EXPECT_EQ(r.truth_events, kIterations);
  ASSERT_EQ(r.clouds.size(), static_cast<size_t>(kIterations));  // seq 0..N-1, each once
  ASSERT_EQ(r.truth.size(), static_cast<size_t>(kIterations));
  EXPECT_EQ(r.clouds.begin()->first, 0);
  EXPECT_EQ(r.clouds.rbegin()->first, kIterations - 1);
  ASSERT_FALSE(r.worlds.empty());
  const std::vector<Rectangle> world = Rectangles(r.worlds.front());
  ASSERT_FALSE(world.empty());

  size_t points = 0, on_walls = 0, beyond_4_sigma = 0;
  double sum_squares = 0.0, worst = 0.0;
  for (const auto& [seq, cloud] : r.clouds) {
    ASSERT_EQ(r.truth.count(seq), 1u) << seq;
    const pose_t& pose = r.truth.at(seq);
    EXPECT_EQ(pose.utime, cloud.utime);
    EXPECT_EQ(pose.status, int8_t{pose_t::STATUS_TRUTH});
    for (const double c : pose.covariance) EXPECT_EQ(c, 0.0) << "the truth is exact";
    const Eigen::Quaterniond q(pose.orientation[0], pose.orientation[1], pose.orientation[2],
                               pose.orientation[3]);
    const Eigen::Vector3d t(pose.position[0], pose.position[1], pose.position[2]);
    EXPECT_GT(cloud.num_points, 1000) << seq;
    for (int i = 0; i < cloud.num_points; ++i) {
      const Eigen::Vector3d p = q * Eigen::Vector3d(cloud.x[i], cloud.y[i], cloud.z[i]) + t;
      bool wall = false;
      const double distance = DistanceToWorld(world, p, 4 * kSigma, &wall);
      ++points;
      on_walls += wall;
      sum_squares += distance * distance;
      worst = std::max(worst, distance);
      beyond_4_sigma += distance > 4 * kSigma;
    }
  }
  ASSERT_GT(points, 0u);
  std::cout << points << " points: rms distance to the true world "
            << std::sqrt(sum_squares / points) << " m, worst " << worst << " m, " << beyond_4_sigma
            << " beyond 4 sigma, " << 100.0 * on_walls / points << "% on walls\n";
  // The noise is Gaussian along the ray and unclipped, so a few points in a hundred thousand
  // lie beyond 4 sigma (two-sided tail 6.3e-5; the incidence angle only shortens the offset).
  EXPECT_LE(static_cast<double>(beyond_4_sigma) / points, 1.5e-4)
      << beyond_4_sigma << " of " << points << " points beyond 4 sigma";
  EXPECT_LT(worst, 6 * kSigma) << "a point far off every true rectangle";
  EXPECT_LE(std::sqrt(sum_squares / points), kSigma);
  EXPECT_GT(static_cast<double>(on_walls) / points, 0.3) << "the walls are barely seen";
}

// ./relplane replay: lcm-logplayer feeds a recorded run's simulator channels, and only those,
// to fresh services (fakes here) on a new bus; the new recording holds every one of them,
// wheel odometry (ODOMETRY, asked for by sim.odometry) included.
TEST(SimRecording, ReplayFeedsTheRecordedSimulatorChannelsToFreshServices) {
  const std::string scenario = SourceDir() + "/scenarios/straight_hallway.yaml";
  TempDir dir;
  const std::string live = dir.Path() + "/live";
  std::string output;
  ASSERT_EQ(
      RunLauncher({scenario, "--out", live, "--lcm-url", TestBusUrl(47116), "--set",
                   "launch.services=[sim]", "--set", "launch.rate_hz=60", "--set",
                   "sim.odometry.enabled=true", "--iterations", "20"},
                  120, &output),
      0)
      << output;

  const std::string bin = dir.Path() + "/bin";
  ASSERT_EQ(mkdir(bin.c_str(), 0755), 0);
  const std::string replay = dir.Path() + "/replay";
  for (const std::string name : {"segmenter", "mapper", "logger"}) {
    // The fake logger scores nothing: its metrics.json expects nothing (no verdict, exit 0).
    const std::string metrics =
        name == "logger" ? "echo '{\"schema\": \"relplane-metrics/1\", \"expect\": []}' > " +
                               replay + "/metrics.json\n"
                         : "";
    WriteFakeService(bin, name,
                     metrics + "echo \"$@\" > " + dir.Path() + "/" + name + ".args\nexec sleep 60");
  }
  ASSERT_EQ(RunLauncher({"--replay", live + "/bus.lcmlog", "--bin-dir", bin, "--out", replay,
                         "--speed", "3", "--lcm-url", TestBusUrl(47117)},
                        120, &output),
            0)
      << output;
  EXPECT_NE(output.find("scenario straight_hallway-replay: segmenter, mapper, logger, logplayer"),
            std::string::npos)
      << output;
  EXPECT_NE(ReadText(dir.Path() + "/logger.args").find("--out " + replay), std::string::npos);
  // The services got the recorded run's scenario.
  EXPECT_EQ(ReadText(replay + "/scenario.yaml"), ReadText(live + "/scenario.yaml"));

  const Recording original = ReadLog(live + "/bus.lcmlog");
  const Recording replayed = ReadLog(replay + "/bus.lcmlog");
  EXPECT_EQ(replayed.cloud_events, 20);
  EXPECT_EQ(replayed.truth_events, 20);
  EXPECT_EQ(original.odometry_events, 20);  // one reading per iteration by default
  ASSERT_EQ(replayed.odometry.size(), original.odometry.size());
  for (size_t k = 0; k < original.odometry.size(); ++k) {
    EXPECT_EQ(replayed.odometry[k].seq, static_cast<int64_t>(k));
    EXPECT_EQ(replayed.odometry[k].position[0], original.odometry[k].position[0]);
  }
  EXPECT_EQ(replayed.worlds.size(), original.worlds.size());
  EXPECT_EQ(replayed.other_events, 0) << "STATUS and the like must not be replayed";
  ASSERT_EQ(replayed.clouds.size(), original.clouds.size());
  for (const auto& [seq, cloud] : original.clouds) {
    EXPECT_EQ(replayed.clouds.at(seq).x, cloud.x) << seq;
  }
}

}  // namespace
}  // namespace relplane::testing
