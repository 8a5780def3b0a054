#pragma once
// PLANES -> mapper input, mapper output -> POSE and MAP.

#include <relplane/map_t.hpp>
#include <relplane/odometry_t.hpp>
#include <relplane/plane_set_t.hpp>
#include <relplane/pose_t.hpp>

#include <string>
#include <vector>

#include "relplane/mapper/mapper.hpp"

namespace relplane::mapper {

// Converts a plane set. Returns false with a one-line reason when the set is unusable as a
// whole (a plane with NaN or infinite numbers, a zero normal, a negative vertex count).
bool FromPlaneSet(const plane_set_t& msg, std::vector<PlaneInput>* planes, std::string* reason);

// `covariance`: of (x, y, yaw), world frame (observability.hpp).
// Converts a wheel odometry reading. False with a one-line reason for non-finite numbers, a
// zero quaternion or a covariance that is not symmetric positive semi-definite.
bool FromOdometry(const odometry_t& msg, OdometryReading* reading, std::string* reason);

// MAP goes out at most once per this much simulated time (utime), when the map changed: the
// service's cadence, which the pipeline bench's profile of the mapper repeats.
inline constexpr int64_t kMapPeriodUs = 100000;

pose_t ToPoseMessage(const PoseEstimate& estimate, const Eigen::Matrix3d& covariance, double z,
                     int64_t utime, int64_t seq);
map_t ToMapMessage(const MapSnapshot& map, int64_t utime, int64_t seq);

}  // namespace relplane::mapper
