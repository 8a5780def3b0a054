#include "relplane/mapper/pose_covariance.hpp"

#include <cmath>

#include "localisation/frustum.hpp"

namespace relplane::mapper {

Observability ObservabilityOf(const PoseEstimate& estimate, const ObservabilityOptions& options) {
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  const bool solved =
      estimate.status == PoseStatus::kTracking || estimate.status == PoseStatus::kMotionModel;
  if (solved) {
    information.topLeftCorner<2, 2>() = estimate.position_information;
    if (std::isfinite(estimate.yaw_sigma) && estimate.yaw_sigma > 0.0) {
      information(2, 2) = 1.0 / (estimate.yaw_sigma * estimate.yaw_sigma);
    }
  }
  return AnalyseInformation(information, options);
}

}  // namespace relplane::mapper
