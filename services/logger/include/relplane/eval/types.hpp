#pragma once
// What the evaluation sees of a run: decoded poses, maps and service reports. Plain structs, no
// LCM, so the logger service and the offline tool feed one recorder
// (services/logger/shell/convert).

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "relplane/common/service_stats.hpp"

namespace relplane::eval {

// Mirrors pose_t's status constants (lcmtypes/pose_t.lcm).
enum class PoseStatus : int {
  kTruth = 0,
  kTracking = 1,
  kMotionModel = 2,
  kInitializing = 3,
  kLost = 4
};

// One pose of the estimate (POSE) or of the truth (SIM_TRUTH): world <- sensor.
struct PoseSample {
  int64_t utime = 0;
  int64_t seq = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  int status = 0;
  // (x, y, yaw), world frame: the estimate's (POSE) or zero (SIM_TRUTH, exact).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

// One plane of a map (MAP or SIM_WORLD), world frame.
struct PlaneRecord {
  int64_t id = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double d = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> vertices;
  int64_t observations = 0;  // num_points: observations in MAP, 0 in SIM_WORLD
  double rms = 0.0;
};

struct GroupRecord {
  int64_t id = 0;
  int64_t basis_id = 0;
  std::vector<int64_t> members;  // plane ids
};

struct MapSnapshot {
  int64_t utime = 0;
  int64_t seq = -1;
  std::vector<PlaneRecord> planes;
  std::vector<GroupRecord> groups;
};

// One STATUS report of one service: the counters every service keeps (ServiceStats), with
// when and from whom.
struct StatusSample : StatusSnapshot {
  int64_t utime = 0;
  std::string service;
};

}  // namespace relplane::eval
