// What the pose solver says the walls of its final solve fix (PoseEstimate::position_information
// and yaw_sigma), checked against the information computed by hand from the walls' geometry.
#include <gtest/gtest.h>

#include <cmath>

#include "comparison/comparison.hpp"
#include "eigen_solver_2d.hpp"
#include "ideal_segmenter.hpp"
#include "localisation/pose_solver.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

Placement Line(const Observation& seen, const Vector2d& point) {
  Placement p;
  p.alpha = seen.Alpha();
  p.point = point;
  p.known = Known::kLine;
  return p;
}

// The heading information of one sighting as the solver weighs it: its fit's sigma (an exact
// fit: the floor, 1 mrad) and a short piece's blur combined.
double HeadingInformation(const Observation& obs) {
  const double sigma = std::hypot(1e-3, PieceBlur(obs, FitOptions{}));
  return 1.0 / (sigma * sigma);
}

TEST(PoseSolverInformation, TwoCrossingWallsFixBothDirectionsAndTheHeading) {
  const geometry::Pose2 truth{1.0, -0.5, 0.1};
  const geometry::Pose2 inv = truth.Inverse();
  const Observation a =
      *MakeObservation(testing::WallSeen(inv * Vector2d(4, -1), inv * Vector2d(4, 1)), 1, 0.3);
  const Observation b =
      *MakeObservation(testing::WallSeen(inv * Vector2d(0, 1), inv * Vector2d(4, 1)), 1, 0.3);
  const RltPlane pa(0, a, 0.05, 100), pb(1, b, 0.05, 100);
  const PoseEstimate est =
      Localise({{&a, &pa, Line(a, {4, -1})}, {&b, &pb, Line(b, {0, 1})}}, {0.9, -0.4, 0.05},
               LearnedFrustum{}, LocalisationOptions{}, FitOptions{});
  ASSERT_EQ(est.status, PoseStatus::kTracking);
  // The two lines' normals are the world's axes: one equation each, each good to the edge noise.
  const double unit = 1.0 / std::pow(LocalisationOptions{}.edge_noise, 2);  // m^-2
  EXPECT_NEAR(est.position_information(0, 0), unit, 1e-9);
  EXPECT_NEAR(est.position_information(1, 1), unit, 1e-9);
  EXPECT_NEAR(est.position_information(0, 1), 0.0, 1e-9);
  const double heading = HeadingInformation(a) + HeadingInformation(b);
  EXPECT_NEAR(est.yaw_sigma, 1.0 / std::sqrt(heading), 1e-15);
}

TEST(PoseSolverInformation, OneWallLeavesTheDirectionAlongItOpen) {
  const geometry::Pose2 truth{1.0, -0.5, 0.0};
  const geometry::Pose2 inv = truth.Inverse();
  const Observation a =
      *MakeObservation(testing::WallSeen(inv * Vector2d(0, 1), inv * Vector2d(4, 1)), 1, 0.3);
  const RltPlane pa(0, a, 0.05, 100);
  const PoseEstimate est = Localise({{&a, &pa, Line(a, {0, 1})}}, {0.9, -0.4, 0.0},
                                    LearnedFrustum{}, LocalisationOptions{}, FitOptions{});
  ASSERT_EQ(est.status, PoseStatus::kMotionModel);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(est.position_information);
  EXPECT_NEAR(eig.eigenvalues()(0), 0.0, 1e-12);
  EXPECT_NEAR(eig.eigenvalues()(1), 1.0 / std::pow(LocalisationOptions{}.edge_noise, 2), 1e-9);
  // The open direction is the wall's (x): its eigenvector has no y part.
  EXPECT_NEAR(std::abs(eig.eigenvectors()(1, 0)), 0.0, 1e-12);
  EXPECT_GT(est.yaw_sigma, 0.0);
}

TEST(PoseSolverInformation, NoWallNoInformation) {
  const PoseEstimate est =
      Localise({}, {0.9, -0.4, 0.0}, LearnedFrustum{}, LocalisationOptions{}, FitOptions{});
  EXPECT_EQ(est.status, PoseStatus::kLost);
  EXPECT_TRUE(est.position_information.isZero());
}

}  // namespace
}  // namespace relplane::mapper
