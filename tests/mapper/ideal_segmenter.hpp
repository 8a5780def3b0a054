#pragma once
// Test fixture: an "ideal segmenter" for a 2½D world of wall rectangles. Given the sensor pose
// and frustum it returns, per wall, the visible part as the plane observation the mapper reads
// (sensor frame, normal towards the sensor, the 4 corners of the visible rectangle), with
// optional noise on the plane parameters and the edges. Also trajectories and the error
// metrics (ATE, map error) the mapper tests use.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "localisation/pose_solver.hpp"
#include "plane_store/observation.hpp"
#include "relplane/common/geometry.hpp"
#include "relplane/mapper/mapper.hpp"
#include "state.hpp"

namespace relplane::mapper::testing {

struct Wall {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  double z0 = 0.0;
  double z1 = 2.5;
};

struct World {
  std::string name;
  std::vector<Wall> walls;
};

struct Frustum {
  double hfov = M_PI / 2.0;  // rad
  double range = 8.0;        // m, horizontal
  double height = 1.0;       // sensor height above the floor
  double min_length = 0.15;  // m: shorter visible parts are not reported
  // The rays a plane's support counts: a grid of `columns` x `rows` evenly spread over hfov and
  // vfov, as the simulator's default 160 x 120 depth sensor over 90 x 60 degrees.
  int columns = 160;
  int rows = 120;
  double vfov = M_PI / 3.0;  // rad
};

struct Noise {
  double angle = 0.0;   // rad, sigma of the normal's direction
  double offset = 0.0;  // m, sigma of d
  double edge = 0.0;    // m, sigma of each edge along the wall
  uint64_t seed = 1;
};

// What is seen of one wall; `wall` is its index in the world.
struct Seen {
  PlaneInput plane;
  int wall = -1;
};

class IdealSegmenter {
 public:
  IdealSegmenter(World world, Frustum frustum, Noise noise = {});
  std::vector<Seen> Observe(const geometry::Pose2& pose);
  std::vector<PlaneInput> Planes(const geometry::Pose2& pose);
  const World& GetWorld() const { return world_; }

 private:
  World world_;
  Frustum frustum_;
  Noise noise_;
  std::mt19937_64 rng_;
};

// A wall from p0 to p1 (sensor frame, 2 m high around the sensor) as the segmenter reports
// it, normal towards the sensor: for hand-built plane sequences.
PlaneInput WallSeen(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1);

// Poses at `rate_hz` driving straight between waypoints at `speed` and turning in place at
// `turn_rate` at each waypoint (the first pose: the first waypoint heading to the second).
std::vector<geometry::Pose2> Drive(const std::vector<Eigen::Vector2d>& waypoints, double speed,
                                   double turn_rate, double rate_hz = 30.0, int laps = 1);

// Worlds used by the tests.
World StraightHallway(double length = 8.5, double width = 2.0);  // closed, from x = -1
World HallwayWithDoors(double length = 14.0, double width = 2.0);
World Office();  // 2 x 2 rooms joined by doors with jambs
// A rectangular loop of hallway (the paper's Fig. 5), centre line from (0,0); with door
// recesses on the outer walls every `recess_spacing` m (0: none).
World HallwayLoop(double sx = 16.0, double sy = 10.0, double width = 2.0,
                  double recess_spacing = 0.0);

struct RunResult {
  double ate_rmse = 0.0;       // m, x-y
  double yaw_rmse = 0.0;       // rad
  double end_error = 0.0;      // m, worst wall-end error over mapped walls with both ends known
  double end_error_any = 0.0;  // m, worst error of the mapped ends that coincide with true ends
  double angle_error = 0.0;    // rad, worst
  int mapped = 0;
  int duplicates = 0;    // mapped walls beyond one per true wall
  int unmatched = 0;     // mapped walls matching no true wall
  int motion_model = 0;  // poses with status MOTION_MODEL
  int lost = 0;
  double max_error = 0.0;     // m, worst pose error
  std::string duplicate_ids;  // per duplicated true wall: the mapped ids on it
};

// Wheel odometry's increment into iteration k (k >= 1), when the run has odometry.
using OdometryFn = std::function<std::optional<OdometryIncrement>(size_t k)>;

// Runs the mapper over the trajectory and scores it against the world.
RunResult Run(Mapper& mapper, IdealSegmenter& segmenter, const std::vector<geometry::Pose2>& poses,
              const OdometryFn& odometry = nullptr);

std::string Describe(const RunResult& r);

}  // namespace relplane::mapper::testing
