// Wheel odometry in the §II.E motion model: it predicts the pose in place of the learnt
// velocity, so it carries the position only along what the walls in view leave open.
#include <gtest/gtest.h>

#include <cmath>

#include "ideal_segmenter.hpp"
#include "motion/motion_model.hpp"

namespace relplane::mapper {
namespace {

OdometryIncrement Increment(const geometry::Pose2& motion, double variance) {
  OdometryIncrement o;
  o.motion = motion;
  o.covariance = Eigen::Matrix3d::Identity() * variance;
  return o;
}

TEST(OdometryMotion, MovesTheLastPoseOnInItsOwnFrame) {
  MotionModel model(MotionOptions{}, LocalisationOptions{}.max_step);
  const Motion m = model.Odometry({1.0, 2.0, M_PI / 2}, Increment({0.05, 0.0, 0.01}, 0.0));
  EXPECT_TRUE(m.known);
  EXPECT_TRUE(m.odometry);
  EXPECT_NEAR(m.predicted.x, 1.0, 1e-12);  // forwards along the heading (+y)
  EXPECT_NEAR(m.predicted.y, 2.05, 1e-12);
  EXPECT_NEAR(m.predicted.yaw, M_PI / 2 + 0.01, 1e-12);
}

TEST(OdometryMotion, ItsErrorGrowsUntilTheWallsFixThePosition) {
  MotionOptions options;
  options.odometry_drift = 0.02;
  MotionModel model(options, LocalisationOptions{}.max_step);
  double sigma = 0.0;
  for (int k = 0; k < 20; ++k) {  // 1 m in 5 cm steps, each with 1e-6 m^2 per axis
    const Motion m = model.Odometry({}, Increment({0.05, 0.0, 0.0}, 1e-6));
    EXPECT_GT(m.sigma, sigma);
    sigma = m.sigma;
  }
  // The reported variance (20 steps x 2 axes x 1e-6) and 2 % of the metre driven.
  EXPECT_NEAR(sigma, std::sqrt(4e-5 + 0.02 * 0.02), 1e-12);
  model.Fixed();
  EXPECT_NEAR(model.Odometry({}, Increment({0.05, 0.0, 0.0}, 0.0)).sigma, 0.02 * 0.05, 1e-12);
}

// Odometry's distance scale is learnt from the spans between poses the walls fixed: wheels that
// read 1 % too far carry the position 1 cm a metre along every stretch the walls leave open, where
// the learnt velocity is nearly exact (on generated worlds with the simulator's default odometry,
// fused runs came out worse than without odometry by 1-4 cm on 38 of 200).
TEST(OdometryMotion, ItsScaleIsLearntFromTheSpansTheWallsFixed) {
  MotionModel model(MotionOptions{}, LocalisationOptions{}.max_step);
  const geometry::Pose2 read{1.01, 0.0, 0.0};  // a metre driven, 1.01 m read
  // A span shorter than motion.odometry_scale_span goes on to the next fixed pose.
  EXPECT_FALSE(model.CalibrateOdometry({}, {0.2, 0.0, 0.0}, {0.202, 0.0, 0.0}));
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(model.CalibrateOdometry({}, {1.0, 0.0, 0.0}, read));
  EXPECT_EQ(model.OdometryScale(), 1.0) << "learnt from 5 spans on";
  // One span across a pose the walls fixed 0.4 m off does not move the median.
  EXPECT_TRUE(model.CalibrateOdometry({}, {1.4, 0.0, 0.0}, read));
  EXPECT_TRUE(model.CalibrateOdometry({}, {1.0, 0.0, 0.0}, read));
  EXPECT_NEAR(model.OdometryScale(), 1.0 / 1.01, 1e-12);
  // The prediction moves on by the scaled reading.
  const Motion m = model.Odometry({2.0, 0.0, M_PI / 2}, Increment({0.0505, 0.0, 0.0}, 0.0));
  EXPECT_NEAR(m.predicted.y, 0.05, 1e-12);
  EXPECT_NEAR(m.predicted.x, 2.0, 1e-12);
}

// The paper's Fig. 5 loop without door recesses: for the first ~7 m of each leg only the two
// side walls are in view, and nothing the planes show fixes the position along the hallway
// (the `hallway_loop` scenario; 6.9 m ATE there). Odometry off by 1 % in distance and turn and
// drifting 0.5 deg per metre, as a calibrated differential-drive robot's. Along such a leg the
// position can be no better than odometry: 1 % of 7 m is 7 cm at its end. The bound below is
// that drift with half again for margin; walls placed on the first lap from the drifted poses
// carry it into the map, so the whole run is held to it, not only the legs.
TEST(OdometryFusion, BridgesTheFeaturelessLegsOfTheHallwayLoop) {
  testing::IdealSegmenter segmenter(testing::HallwayLoop(), testing::Frustum{});
  const std::vector<geometry::Pose2> poses =
      testing::Drive({{0, 0}, {14, 0}, {14, 8}, {0, 8}, {0, 0}}, 1.5, 1.0);
  auto odometry = [&](size_t k) {
    const geometry::Pose2 truth = poses[k - 1].Inverse() * poses[k];
    const double distance = truth.Translation().norm();
    const geometry::Pose2 read{truth.x * 1.01, truth.y * 1.01,
                               truth.yaw * 1.01 + distance * 0.5 * M_PI / 180.0};
    return std::optional<OdometryIncrement>(Increment(read, 1e-8));
  };
  Mapper without;
  const testing::RunResult alone = testing::Run(without, segmenter, poses);
  ASSERT_GT(alone.ate_rmse, 1.0) << "the loop was observable without odometry: the test shows "
                                    "nothing; "
                                 << testing::Describe(alone);
  Mapper with;
  const testing::RunResult fused = testing::Run(with, segmenter, poses, odometry);
  const double leg_drift = 0.01 * 7.0;
  EXPECT_LT(fused.ate_rmse, leg_drift) << testing::Describe(fused);
  EXPECT_LT(fused.max_error, 1.5 * leg_drift) << testing::Describe(fused);
  EXPECT_EQ(fused.lost, 0) << testing::Describe(fused);
}

// Where the walls fix every direction, odometry decides nothing: a wildly wrong odometry (a
// quarter of the distance) leaves a hallway whose end wall stays in view as accurate
// as without it.
TEST(OdometryFusion, DecidesNothingTheWallsFix) {
  testing::IdealSegmenter segmenter(testing::StraightHallway(), testing::Frustum{});
  const std::vector<geometry::Pose2> poses = testing::Drive({{0, 0}, {6, 0}}, 1.0, 1.0);
  auto wrong = [&](size_t k) {
    const geometry::Pose2 truth = poses[k - 1].Inverse() * poses[k];
    return std::optional<OdometryIncrement>(
        Increment({truth.x * 0.25, truth.y * 0.25, truth.yaw}, 1e-8));
  };
  Mapper reference;
  const testing::RunResult alone = testing::Run(reference, segmenter, poses);
  Mapper with;
  const testing::RunResult fused = testing::Run(with, segmenter, poses, wrong);
  ASSERT_EQ(alone.motion_model, 0) << "the walls left a direction open: the test shows nothing";
  EXPECT_LT(fused.max_error, alone.max_error + 0.005) << testing::Describe(fused);
}

// An increment farther than the platform moves in an iteration (a reset odometry frame, a bad
// message) is refused and said so; the pose is the planes' as without odometry.
TEST(OdometryFusion, AnImpossibleIncrementIsRefusedAndSaid) {
  testing::IdealSegmenter segmenter(testing::StraightHallway(), testing::Frustum{});
  const std::vector<geometry::Pose2> poses = testing::Drive({{0, 0}, {3, 0}}, 1.0, 1.0);
  Mapper with, without;
  for (size_t k = 0; k < poses.size(); ++k) {
    std::optional<OdometryIncrement> odometry;
    if (k > 0) {
      odometry = Increment(poses[k - 1].Inverse() * poses[k], 1e-8);
      if (k == 40) odometry->motion.x = 1e6;
    }
    const auto planes = segmenter.Planes(poses[k]);
    const PoseEstimate a = with.Process(static_cast<int64_t>(k), planes, odometry);
    const PoseEstimate b = without.Process(static_cast<int64_t>(k), planes);
    EXPECT_EQ(a.odometry_refused, k == 40) << k;
    EXPECT_FALSE(b.odometry_refused);
    if (k == 40) {
      EXPECT_EQ(a.status, PoseStatus::kTracking);
      EXPECT_LT((a.pose.Translation() - poses[k].Translation()).norm(), 0.01);
    }
  }
}

}  // namespace
}  // namespace relplane::mapper
