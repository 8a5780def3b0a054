#pragma once
// What the mapper takes in (PlaneInput, as PLANES carries it) and gives out (PoseEstimate, as
// POSE carries it; MapSnapshot, as MAP does).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "relplane/common/geometry.hpp"

namespace relplane::mapper {

// A plane in the sensor frame (x forward, y left, z up), as PLANES carries it.
struct PlaneInput {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // unit, towards the sensor
  double d = 0.0;                                     // normal . p + d = 0
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> vertices;  // visible extent (4 corners of a wall's rectangle)
  int support = 0;
  double rms = 0.0;
};

enum class PoseStatus { kTracking, kMotionModel, kInitializing, kLost };

// The iteration's pose (world <- sensor) and how it was found (§II.D, §II.E).
struct PoseEstimate {
  geometry::Pose2 pose;
  PoseStatus status = PoseStatus::kLost;
  int planes = 0;  // planes used
  // The §II.E motion model moved the position along the heading to a wall end seen uncut from
  // poses the walls fixed (no motion known, walls leaving that direction open).
  bool end_moved = false;
  // rad: how far off the heading may be (the walls' fit sigmas and short-piece bias combined).
  double yaw_sigma = 0.0;
  // What the walls' lines and ends in view fixed of the position, without the previous pose
  // or the learnt velocity's prediction, in m^-2: the sum of w d d^T over the solve's equations,
  // weight 1 / edge_noise^2 for a line good to LocalisationOptions::edge_noise
  // (pose_covariance.hpp turns it into a covariance; its small eigenvalues are the directions
  // the walls leave open).
  Eigen::Matrix2d position_information = Eigen::Matrix2d::Zero();
  // The odometry given with the planes was not used: it moved farther than the platform can
  // (LocalisationOptions::max_step an iteration) or was not finite; the learnt velocity stood in.
  bool odometry_refused = false;
};

// A mapped wall in the world frame (what MAP carries).
struct MappedPlane {
  int64_t id = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double d = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> vertices;  // the wall's rectangle, ends at its edges
  int64_t observations = 0;
  bool both_ends_known = false;
  bool end_known[2] = {false, false};  // vertices[0] (lo) and vertices[1] (hi) are wall ends
};

struct MappedGroup {
  int64_t id = 0;
  int64_t basis = 0;
  std::vector<int64_t> members;
};

struct MapSnapshot {
  std::vector<MappedPlane> planes;
  std::vector<MappedGroup> groups;
};

// Counts of what the mapper holds, for status lines and benchmarks.
struct MapperStats {
  size_t planes = 0;        // rltplanes
  size_t observations = 0;  // kept over all rltplanes
  size_t comparisons = 0;
  size_t groups = 0;
  size_t map_planes = 0;  // planes in the global map
  int graph_solves = 0;   // pose graph solutions run so far
};

}  // namespace relplane::mapper
