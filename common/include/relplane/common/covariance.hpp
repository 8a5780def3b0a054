#pragma once
// Checks on the 3x3 (x, y, yaw) covariances carried by pose_t and odometry_t (row-major).

#include <Eigen/Core>
#include <string>

namespace relplane::geometry {

// True for a finite, symmetric, positive semi-definite covariance; false with a one-line
// reason otherwise (a hostile or broken message must be rejected, not drawn or fused).
bool ValidCovariance(const double row_major[9], std::string* reason);

Eigen::Matrix3d CovarianceFromRowMajor(const double row_major[9]);
void CovarianceToRowMajor(const Eigen::Matrix3d& covariance, double row_major[9]);

}  // namespace relplane::geometry
