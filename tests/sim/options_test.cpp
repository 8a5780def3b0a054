// The `sim` section loader: defaults, the scenarios, and one-line errors naming file, line
// and key.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "options_yaml.hpp"

namespace relplane::sim {
namespace {

ServiceOptions FromText(const std::string& yaml) {
  return ReadServiceOptions(config::Reader::FromString(yaml, "test.yaml", "sim"));
}

// The error's text when loading `yaml` fails; the test fails when it loads.
std::string ErrorOf(const std::string& yaml) {
  try {
    FromText(yaml);
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "loaded without error:\n" << yaml;
  return "";
}

TEST(SimOptions, DefaultsWithoutAFile) {
  const ServiceOptions o = LoadServiceOptions("");
  EXPECT_EQ(o.sim.rate_hz, 30.0);
  EXPECT_EQ(o.sim.sensor.width, 160);
  EXPECT_EQ(o.sim.sensor.height, 120);
  EXPECT_EQ(o.sim.sensor.hfov_deg, 90.0);
  EXPECT_EQ(o.sim.sensor.vfov_deg, 60.0);
  EXPECT_EQ(o.sim.sensor.max_range, 8.0);
  EXPECT_EQ(o.sim.sensor.mount_height, 1.0);
  EXPECT_EQ(o.sim.sensor.noise_sigma, 0.0);
  EXPECT_EQ(o.start_delay, 0.3);
  EXPECT_EQ(o.sim.world.generators.size(), 1u);
}

TEST(SimOptions, ReadsEverySection) {
  const ServiceOptions o = FromText(R"(
sim:
  rate_hz: 15
  start_delay: 0
  world:
    height: 3
    ceiling: false
    generators:
      - {type: office, rooms: [2, 3], room_size: [4, 4], door_width: 1.0, frame_depth: 0}
    walls:
      - {from: [0, 0], to: [1, 0], height: 1}
    rectangles:
      - {origin: [0, 0, 0], u: [1, 0, 0], v: [0, 0, 1]}
  trajectory:
    waypoints: [{x: 0, y: 0}, {x: 4, y: 0}, {x: 4, y: 4}]
    speed: 0.5
    turn_rate: 1
    turn: smooth
    laps: 2
    closed: true
    drive_back: true
  sensor: {width: 64, height: 48, noise_sigma: 0.01, dropout: 0.1, seed: 9}
)");
  EXPECT_EQ(o.sim.rate_hz, 15.0);
  EXPECT_EQ(o.start_delay, 0.0);
  EXPECT_EQ(o.sim.world.height, 3.0);
  EXPECT_FALSE(o.sim.world.ceiling);
  ASSERT_EQ(o.sim.world.generators.size(), 1u);
  const auto& office = std::get<OfficeParams>(o.sim.world.generators[0]);
  EXPECT_EQ(office.rooms, Eigen::Vector2i(2, 3));
  EXPECT_EQ(office.frame_depth, 0.0);
  ASSERT_EQ(o.sim.world.walls.size(), 1u);
  EXPECT_EQ(o.sim.world.walls[0].height, 1.0);
  ASSERT_EQ(o.sim.world.rectangles.size(), 1u);
  ASSERT_EQ(o.sim.trajectory.waypoints.size(), 3u);
  EXPECT_EQ(o.sim.trajectory.waypoints[2], Eigen::Vector2d(4, 4));
  EXPECT_EQ(o.sim.trajectory.turn, TurnMode::kSmooth);
  EXPECT_EQ(o.sim.trajectory.laps, 2);
  EXPECT_TRUE(o.sim.trajectory.drive_back);
  EXPECT_EQ(o.sim.sensor.width, 64);
  EXPECT_EQ(o.sim.sensor.seed, 9u);
  EXPECT_EQ(o.sim.sensor.dropout, 0.1);
}

TEST(SimOptions, ScenariosLoadAndRun) {
  // Every scenario file, so a new one is checked the day it is written.
  std::vector<std::string> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(RELPLANE_SOURCE_DIR) + "/scenarios")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 7u);
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const ServiceOptions o = LoadServiceOptions(file);
    EXPECT_EQ(o.sim.sensor.noise_sigma, 0.0) << "noise is off unless overridden";
    Simulation sim(o.sim);
    // Short enough for tests: well under two minutes of simulated time.
    EXPECT_LT(sim.NumIterations(), 120 * 30);
    EXPECT_GT(sim.Frame(0).points.size(), 1000u);
    // The sensor keeps at least 0.5 m from every wall all the way.
    ASSERT_GT(sim.NumIterations(), 0);
    double closest = 1e9;
    for (int64_t k = 0; k < sim.NumIterations(); ++k) {
      const geometry::Pose2 pose = sim.PlanarPose(k);
      for (const Rect& r : sim.GetWorld().rects) {
        // Walls at the sensor's height (a lintel above a door is passed beneath).
        const double z0 = std::min(r.origin.z(), (r.origin + r.v).z());
        const double z1 = std::max(r.origin.z(), (r.origin + r.v).z());
        const double h = o.sim.sensor.mount_height;
        if (std::abs(r.Normal().z()) > 0.1 || h < z0 || h > z1) continue;
        const geometry::Segment2 footprint{r.origin.head<2>(), (r.origin + r.u).head<2>()};
        closest = std::min(closest, footprint.DistanceTo(pose.Translation()));
      }
    }
    EXPECT_GE(closest, 0.5);
  }
}

TEST(SimOptions, UnknownKeyNamesFileLineAndKey) {
  const std::string e = ErrorOf("name: x\nsim:\n  rate_hz: 30\n  sensor:\n    widht: 10\n");
  EXPECT_NE(e.find("test.yaml:5"), std::string::npos) << e;
  EXPECT_NE(e.find("sim.sensor.widht"), std::string::npos) << e;
  EXPECT_NE(e.find("width"), std::string::npos) << "did-you-mean: " << e;
}

TEST(SimOptions, UnknownKeyInsideAListItem) {
  const std::string e =
      ErrorOf("sim:\n  world:\n    generators:\n      - type: hallway_loop\n        widht: 2\n");
  EXPECT_NE(e.find("test.yaml:5"), std::string::npos) << e;
  EXPECT_NE(e.find("sim.world.generators[0].widht"), std::string::npos) << e;
}

TEST(SimOptions, HallwayLoopRecesses) {
  const ServiceOptions o = FromText(
      "sim:\n  world:\n    generators:\n      - {type: hallway_loop, recess_spacing: 4, "
      "recess_width: 1.2, recess_depth: 0.5}\n");
  const auto& p = std::get<HallwayLoopParams>(o.sim.world.generators.at(0));
  EXPECT_EQ(p.recess_spacing, 4.0);
  EXPECT_EQ(p.recess_width, 1.2);
  EXPECT_EQ(p.recess_depth, 0.5);
  const auto& d = std::get<HallwayLoopParams>(
      FromText("sim:\n  world:\n    generators:\n      - {type: hallway_loop}\n")
          .sim.world.generators.at(0));
  EXPECT_EQ(d.recess_spacing, 0.0) << "no recesses unless asked for";
  const std::string head = "sim:\n  world:\n    generators:\n      - type: hallway_loop\n";
  std::string e = ErrorOf(head + "        recess_spacing: -1\n");
  EXPECT_NE(e.find("recess_spacing"), std::string::npos) << e;
  EXPECT_NE(e.find("negative"), std::string::npos) << e;
  e = ErrorOf(head + "        recess_depth: 0\n");
  EXPECT_NE(e.find("recess_depth"), std::string::npos) << e;
  e = ErrorOf(head + "        recess_width: -0.5\n");
  EXPECT_NE(e.find("recess_width"), std::string::npos) << e;
  e = ErrorOf(head + "        recess_spacing: 1\n        recess_width: 1\n");
  EXPECT_NE(e.find("recess_width"), std::string::npos) << e;
  EXPECT_NE(e.find("less than recess_spacing"), std::string::npos) << e;
}

TEST(SimOptions, OdometryIsOffByDefaultAndReadsItsNamedUnits) {
  EXPECT_FALSE(FromText("").odometry.enabled);
  const ServiceOptions o = FromText(
      "sim:\n  odometry:\n    enabled: true\n    rate: 50\n    scale_error_percent: -0.5\n"
      "    heading_drift_deg_per_m: 1.5\n    noise_deg_per_sqrt_m: 0.1\n    seed: 9\n");
  EXPECT_TRUE(o.odometry.enabled);
  EXPECT_EQ(o.odometry.rate_hz, 50.0);
  EXPECT_EQ(o.odometry.scale_error_percent, -0.5);
  EXPECT_EQ(o.odometry.heading_drift_deg_per_m, 1.5);
  EXPECT_EQ(o.odometry.noise_deg_per_sqrt_m, 0.1);
  EXPECT_EQ(o.odometry.turn_noise_percent, OdometryOptions{}.turn_noise_percent);
  EXPECT_EQ(o.odometry.seed, 9u);
}

TEST(SimOptions, NegativeRate) {
  const std::string e = ErrorOf("sim:\n  rate_hz: -5\n");
  EXPECT_NE(e.find("test.yaml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("sim.rate_hz"), std::string::npos) << e;
  EXPECT_NE(e.find("positive"), std::string::npos) << e;
}

TEST(SimOptions, EmptyWorld) {
  const std::string e = ErrorOf("sim:\n  world:\n    generators: []\n");
  EXPECT_NE(e.find("test.yaml:3"), std::string::npos) << e;
  EXPECT_NE(e.find("sim.world.generators"), std::string::npos) << e;
  EXPECT_NE(e.find("empty"), std::string::npos) << e;
}

TEST(SimOptions, MissingFile) {
  try {
    LoadServiceOptions("/nonexistent/scenario.yaml");
    ADD_FAILURE() << "loaded a missing file";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scenario.yaml"), std::string::npos);
  }
}

TEST(SimOptions, CameraModelByNameWithItsParameters) {
  EXPECT_EQ(FromText("").sim.sensor.camera.name, "gaussian");
  const ServiceOptions o =
      FromText("sim:\n  sensor:\n    model: kinect_v1\n    baseline: 0.08\n    max_depth: 4.5\n");
  const camera::DepthCameraModel& c = o.sim.sensor.camera;
  EXPECT_EQ(c.name, "kinect_v1");
  EXPECT_EQ(c.baseline, 0.08);
  EXPECT_EQ(c.max_depth, 4.5);
  EXPECT_EQ(c.focal_px, camera::Preset("kinect_v1")->focal_px) << "the rest from the preset";
  EXPECT_EQ(FromText("sim:\n  sensor:\n    model: tof\n").sim.sensor.camera.name, "tof");
}

TEST(SimOptions, ImpossibleValuesNameTheirKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"sim:\n  world:\n    generators: [{type: maze}]\n", "sim.world.generators[0].type"},
      {"sim:\n  world:\n    generators: [{length: 3}]\n", "sim.world.generators[0].type"},
      {"sim:\n  world:\n    generators: [{type: office, rooms: [0, 2]}]\n", ".rooms"},
      {"sim:\n  world:\n    rectangles: [{origin: [0,0,0], u: [1,0,0], v: [1,1,0]}]\n",
       "sim.world.rectangles[0].v"},
      {"sim:\n  world:\n    walls: [{from: [0, 0], to: [0, 0]}]\n", "sim.world.walls[0].to"},
      {"sim:\n  world:\n    walls: [{from: [0, 0, 1], to: [1, 0]}]\n", "sim.world.walls[0].from"},
      {"sim:\n  trajectory:\n    waypoints: [{x: 0, y: 0}]\n", "sim.trajectory.waypoints"},
      {"sim:\n  trajectory:\n    laps: 2\n", "sim.trajectory.laps"},
      {"sim:\n  trajectory:\n    turn: sideways\n", "sim.trajectory.turn"},
      {"sim:\n  trajectory:\n    speed: 0\n", "sim.trajectory.speed"},
      {"sim:\n  sensor:\n    hfov_deg: 180\n", "sim.sensor.hfov_deg"},
      {"sim:\n  sensor:\n    dropout: 1\n", "sim.sensor.dropout"},
      {"sim:\n  sensor:\n    noise_sigma: -0.1\n", "sim.sensor.noise_sigma"},
      {"sim:\n  sensor:\n    width: many\n", "sim.sensor.width"},
      {"sim:\n  start_delay: -1\n", "sim.start_delay"},
      {"sim:\n  sensor:\n    model: kinect\n", "sim.sensor.model"},
      {"sim:\n  sensor:\n    model: kinect_v1\n    noise_sigma: 0.01\n",
       "sim.sensor.noise_sigma"},
      {"sim:\n  sensor:\n    baseline: 0.1\n", "sim.sensor.baseline"},
      {"sim:\n  sensor:\n    model: tof\n    max_depth: 0.2\n", "sim.sensor.max_depth"},
      {"sim:\n  sensor:\n    model: kinect_v1\n    max_incidence_deg: 95\n",
       "sim.sensor.max_incidence_deg"},
      {"sim:\n  odometry:\n    rate: -1\n", "sim.odometry.rate"},
      {"sim:\n  odometry:\n    scale_eror_percent: 1\n", "sim.odometry.scale_eror_percent"},
      {"sim:\n  odometry:\n    heading_drift_deg_per_m: .nan\n", "sim.odometry.heading_drift"},
      {"sim:\n  odometry:\n    noise_m_per_sqrt_m: -0.01\n", "sim.odometry.noise_m_per_sqrt_m"},
  };
  for (const auto& [yaml, key] : cases) {
    const std::string e = ErrorOf(yaml);
    EXPECT_NE(e.find(key), std::string::npos) << "expected key " << key << " in: " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << "one line: " << e;
    EXPECT_EQ(e.rfind("test.yaml:", 0), 0u) << e;
  }
}

}  // namespace
}  // namespace relplane::sim
