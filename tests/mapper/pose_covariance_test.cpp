// The covariance POSE carries, from what a frame's localisation used.
#include "relplane/mapper/pose_covariance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "localisation/frustum.hpp"

namespace relplane::mapper {
namespace {

TEST(PoseCovariance, OneWallLeavesItsDirectionAtThePrior) {
  PoseEstimate est;
  est.status = PoseStatus::kMotionModel;
  const double noise = LocalisationOptions{}.edge_noise;
  est.position_information << 1.0 / (noise * noise), 0.0, 0.0, 0.0;  // one line, normal along x
  est.yaw_sigma = 0.002;
  const ObservabilityOptions options;
  const Observability o = ObservabilityOf(est, options);
  ASSERT_EQ(o.unconstrained.size(), 1u);
  EXPECT_GT(std::abs(o.unconstrained[0].y()), 0.999);
  EXPECT_NEAR(std::sqrt(o.covariance(0, 0)), noise, 1e-4);
  EXPECT_NEAR(std::sqrt(o.covariance(1, 1)), options.prior_sigma_position, 1e-6);
  EXPECT_NEAR(std::sqrt(o.covariance(2, 2)), 0.002, 1e-6);
}

TEST(PoseCovariance, TrackingOnTwoWallsIsConstrained) {
  PoseEstimate est;
  est.status = PoseStatus::kTracking;
  est.position_information << 2.0, 0.3, 0.3, 1.0;
  est.position_information /= 0.03 * 0.03;  // two lines good to 3 cm, m^-2
  est.yaw_sigma = 0.003;
  EXPECT_TRUE(ObservabilityOf(est).FullyConstrained());
}

TEST(PoseCovariance, NoSolveMeansThePrior) {
  PoseEstimate est;
  est.status = PoseStatus::kLost;
  est.position_information << 2.0, 0.0, 0.0, 2.0;  // stale: not this frame's
  est.yaw_sigma = 0.003;
  const ObservabilityOptions options;
  const Observability o = ObservabilityOf(est, options);
  EXPECT_EQ(o.unconstrained.size(), 3u);
  EXPECT_NEAR(o.covariance(2, 2), options.prior_sigma_yaw * options.prior_sigma_yaw, 1e-12);
}

}  // namespace
}  // namespace relplane::mapper
