#pragma once
// Simulator types -> relplane messages (the only place the simulator meets lcm-gen types).

#include <Eigen/Geometry>
#include <relplane/map_t.hpp>
#include <relplane/odometry_t.hpp>
#include <relplane/point_cloud_t.hpp>
#include <relplane/pose_t.hpp>
#include <vector>

#include "relplane/sim/depth_sensor.hpp"
#include "relplane/sim/odometry.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane::sim {

// SENSOR_POINTS: the scan's points in the sensor frame.
point_cloud_t ToPointCloud(const Scan& scan, int64_t seq, int64_t utime);
// SIM_TRUTH: the true sensor pose (world <- sensor), covariance zero.
pose_t ToTruthPose(const Eigen::Isometry3d& pose, int64_t seq, int64_t utime);
// ODOMETRY: a wheel odometry reading, at height 0 of the odometry frame.
odometry_t ToOdometry(const OdometryReading& reading, int64_t utime);
// SIM_WORLD: one plane per true rectangle, id = index, 4 corners, no groups.
map_t ToWorldMap(const std::vector<TruePlane>& planes, int64_t seq, int64_t utime);

}  // namespace relplane::sim
