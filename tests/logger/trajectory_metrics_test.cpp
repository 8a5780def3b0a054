// Trajectory metrics against hand-made trajectories with known answers.
#include "relplane/eval/trajectory_metrics.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "fixtures.hpp"

namespace relplane::eval {
namespace {

using testing::LoopInRoom;
using testing::Pose;

// The estimate is the truth moved by the planar motion `t` (applied to position and yaw).
std::vector<PoseSample> Moved(const std::vector<PoseSample>& truth, const geometry::Pose2& t) {
  std::vector<PoseSample> out;
  for (const PoseSample& p : truth) {
    const geometry::Pose2 moved =
        t * geometry::Pose2{p.position.x(), p.position.y(), geometry::YawOf(p.orientation)};
    out.push_back(Pose(p.seq, moved.x, moved.y, moved.yaw));
  }
  return out;
}

TEST(TrajectoryMetrics, ConstantOffsetGivesThatAteAndAlignsAway) {
  const std::vector<PoseSample> truth = LoopInRoom();
  const std::vector<PoseSample> estimate = Moved(truth, {0.3, -0.4, 0.0});
  const TrajectoryMetrics m = ComputeTrajectoryMetrics(MatchBySeq(estimate, truth), 1.0);
  EXPECT_EQ(m.matched, static_cast<int64_t>(truth.size()));
  EXPECT_NEAR(m.ate_rmse_m, 0.5, 1e-9);
  EXPECT_NEAR(m.ate_max_m, 0.5, 1e-9);
  EXPECT_NEAR(m.ate_final_m, 0.5, 1e-9);
  EXPECT_NEAR(m.ate_aligned_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(m.alignment.x, -0.3, 1e-9);
  EXPECT_NEAR(m.alignment.y, 0.4, 1e-9);
  EXPECT_NEAR(m.yaw_rmse_deg, 0.0, 1e-9);
  // A constant offset leaves every relative motion exact.
  EXPECT_GT(m.rpe_segments, 5);
  EXPECT_NEAR(m.rpe_translation_per_m, 0.0, 1e-9);
}

TEST(TrajectoryMetrics, RotationIsAlignedAwayBySe2Alignment) {
  const std::vector<PoseSample> truth = LoopInRoom();
  const geometry::Pose2 drift{1.0, 2.0, 10.0 * M_PI / 180.0};
  const std::vector<PoseSample> estimate = Moved(truth, drift);
  const TrajectoryMetrics m = ComputeTrajectoryMetrics(MatchBySeq(estimate, truth), 1.0);
  EXPECT_GT(m.ate_rmse_m, 1.0);
  EXPECT_NEAR(m.ate_aligned_rmse_m, 0.0, 1e-9);
  // The alignment found is the inverse of the drift.
  const geometry::Pose2 inverse = drift.Inverse();
  EXPECT_NEAR(m.alignment.yaw, inverse.yaw, 1e-9);
  EXPECT_NEAR(m.alignment.x, inverse.x, 1e-9);
  EXPECT_NEAR(m.alignment.y, inverse.y, 1e-9);
  EXPECT_NEAR(m.yaw_rmse_deg, 10.0, 1e-9);
  EXPECT_NEAR(m.yaw_max_deg, 10.0, 1e-9);
  // A rigid motion of the whole trajectory changes no relative pose.
  EXPECT_NEAR(m.rpe_translation_per_m, 0.0, 1e-9);
  EXPECT_NEAR(m.rpe_rotation_deg_per_m, 0.0, 1e-9);
}

TEST(TrajectoryMetrics, AlignSe2MatchesAKnownMotionOnRandomPoints) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-10.0, 10.0);
  const geometry::Pose2 truth_motion{-3.0, 0.5, 2.5};
  std::vector<Eigen::Vector2d> source, target;
  for (int i = 0; i < 50; ++i) {
    source.emplace_back(coord(rng), coord(rng));
    target.push_back(truth_motion * source.back());
  }
  const geometry::Pose2 found = AlignSE2(source, target);
  EXPECT_NEAR(found.x, truth_motion.x, 1e-9);
  EXPECT_NEAR(found.y, truth_motion.y, 1e-9);
  EXPECT_NEAR(geometry::WrapAngle(found.yaw - truth_motion.yaw), 0.0, 1e-9);
}

TEST(TrajectoryMetrics, AlignSe2AgreesWithEigensUmeyamaOnNoisyPoints) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-10.0, 10.0);
  std::normal_distribution<double> noise(0.0, 0.3);
  const geometry::Pose2 motion{2.0, -1.0, -0.7};
  Eigen::Matrix2Xd source(2, 40), target(2, 40);
  std::vector<Eigen::Vector2d> src, dst;
  for (int i = 0; i < 40; ++i) {
    src.emplace_back(coord(rng), coord(rng));
    dst.push_back(motion * src.back() + Eigen::Vector2d(noise(rng), noise(rng)));
    source.col(i) = src.back();
    target.col(i) = dst.back();
  }
  const Eigen::Matrix3d reference = Eigen::umeyama(source, target, false);
  const geometry::Pose2 found = AlignSE2(src, dst);
  EXPECT_NEAR(found.x, reference(0, 2), 1e-9);
  EXPECT_NEAR(found.y, reference(1, 2), 1e-9);
  EXPECT_NEAR(found.yaw, std::atan2(reference(1, 0), reference(0, 0)), 1e-9);
}

TEST(TrajectoryMetrics, ScaleDriftShowsAsRelativeErrorPerMetre) {
  std::vector<PoseSample> truth, estimate;
  for (int i = 0; i <= 100; ++i) {
    truth.push_back(Pose(i, 0.05 * i, 0.0, 0.0));
    estimate.push_back(Pose(i, 1.1 * 0.05 * i, 0.0, 0.0));  // 10 % too long
  }
  const TrajectoryMetrics m = ComputeTrajectoryMetrics(MatchBySeq(estimate, truth), 1.0);
  EXPECT_NEAR(m.path_length_m, 5.0, 1e-9);
  EXPECT_NEAR(m.rpe_translation_per_m, 0.1, 1e-6);
  EXPECT_NEAR(m.ate_final_m, 0.5, 1e-9);
}

TEST(TrajectoryMetrics, MatchesBySeqOnly) {
  const std::vector<PoseSample> truth = {Pose(0, 0, 0, 0), Pose(1, 1, 0, 0), Pose(2, 2, 0, 0)};
  // seq 5 has no truth; seq 1 arrives twice and the later one counts.
  const std::vector<PoseSample> estimate = {Pose(1, 9, 0, 0), Pose(5, 0, 0, 0), Pose(1, 1, 1, 0),
                                            Pose(0, 0, 0, 0)};
  const std::vector<MatchedPose> matched = MatchBySeq(estimate, truth);
  ASSERT_EQ(matched.size(), 2u);
  EXPECT_EQ(matched[0].truth.seq, 0);
  EXPECT_EQ(matched[1].truth.seq, 1);
  const TrajectoryMetrics m = ComputeTrajectoryMetrics(matched, 1.0);
  EXPECT_NEAR(m.ate_rmse_m, std::sqrt(0.5), 1e-9);
}

TEST(TrajectoryMetrics, NoMatchesGiveNoNumbers) {
  const TrajectoryMetrics m = ComputeTrajectoryMetrics({}, 1.0);
  EXPECT_EQ(m.matched, 0);
  EXPECT_TRUE(std::isnan(m.ate_rmse_m));
  EXPECT_TRUE(std::isnan(m.rpe_translation_per_m));
}

}  // namespace
}  // namespace relplane::eval

namespace relplane::eval {
namespace {

// Gaussian errors drawn from a known covariance: a consistent estimate keeps about 98.9 % of
// its frames within 3 sigma (2 dof); claiming a tenth of the true sigma keeps far fewer.
TEST(TrajectoryMetrics, ConsistencyCountsFramesWithinThreeSigma) {
  std::vector<PoseSample> truth;  // a slow turn, so along and across change direction
  for (int i = 0; i < 2000; ++i) truth.push_back(testing::Pose(i, 0.01 * i, 0.0, 0.003 * i));
  std::mt19937 rng(7);
  std::normal_distribution<double> unit(0.0, 1.0);
  const double sigma_x = 0.05, sigma_y = 0.02, sigma_yaw = 0.01;
  const auto estimate = [&](double claimed) {
    std::vector<PoseSample> out;
    for (const PoseSample& p : truth) {
      PoseSample e = testing::Pose(p.seq, p.position.x() + sigma_x * unit(rng),
                                   p.position.y() + sigma_y * unit(rng),
                                   geometry::YawOf(p.orientation) + sigma_yaw * unit(rng));
      e.status = p.seq % 2 == 0 ? 1 : 2;
      e.covariance.diagonal() << std::pow(claimed * sigma_x, 2), std::pow(claimed * sigma_y, 2),
          std::pow(claimed * sigma_yaw, 2);
      out.push_back(e);
    }
    return out;
  };
  const TrajectoryMetrics honest = ComputeTrajectoryMetrics(MatchBySeq(estimate(1.0), truth), 1.0);
  ASSERT_GT(truth.size(), 200u);
  EXPECT_EQ(honest.consistency.frames, static_cast<int64_t>(truth.size()));
  EXPECT_GT(honest.consistency.position_within_3sigma, 0.97);
  EXPECT_GT(honest.consistency.yaw_within_3sigma, 0.98);
  EXPECT_EQ(honest.consistency_by_status[1].frames + honest.consistency_by_status[2].frames,
            honest.consistency.frames);
  const TrajectoryMetrics sure = ComputeTrajectoryMetrics(MatchBySeq(estimate(0.1), truth), 1.0);
  EXPECT_LT(sure.consistency.position_within_3sigma, 0.5);
  EXPECT_LT(sure.consistency.yaw_within_3sigma, 0.5);
  // The signed along/across errors and their sigmas are there for error.svg's band.
  for (const ErrorSample& e : honest.errors) {
    EXPECT_NEAR(std::hypot(e.along_m, e.across_m), e.position_m, 1e-9);
    EXPECT_GE(e.sigma_along_m, std::min(sigma_x, sigma_y) - 1e-12);
    EXPECT_LE(e.sigma_along_m, std::max(sigma_x, sigma_y) + 1e-12);
  }
}

TEST(TrajectoryMetrics, AZeroCovarianceHoldsOnlyAZeroError) {
  EXPECT_TRUE(PositionWithin3Sigma(Eigen::Vector2d::Zero(), Eigen::Matrix2d::Zero()));
  EXPECT_FALSE(PositionWithin3Sigma(Eigen::Vector2d(1e-3, 0), Eigen::Matrix2d::Zero()));
  Eigen::Matrix2d c;
  c << 0.01, 0.0, 0.0, 1e-4;  // sigma 0.1 m along x, 0.01 m along y
  EXPECT_TRUE(PositionWithin3Sigma({0.25, 0.0}, c));
  EXPECT_FALSE(PositionWithin3Sigma({0.0, 0.05}, c));
  EXPECT_TRUE(YawWithin3Sigma(0.029, 1e-4));
  EXPECT_FALSE(YawWithin3Sigma(0.031, 1e-4));
}

}  // namespace
}  // namespace relplane::eval
