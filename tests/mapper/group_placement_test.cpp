// §II.D the least squares placing a group on the global map (SolveGroupPlacement), on links
// built by hand: the rotation from the links' orientations, the translation from their lines,
// and the prior only in the directions no line fixes.
#include "global_map/group_placement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "group_fixtures.hpp"
#include "relplane/common/geometry.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;
using testing::Placed;

// A line of the group's frame (orientation `alpha` through `point`) and the same line where
// `truth` puts it in the world.
GroupLink LineLink(const geometry::Pose2& truth, double alpha, const Vector2d& point,
                   const RltPlane& plane) {
  return {Placed(alpha, point, -1, Known::kLine),
          Placed(geometry::WrapAngle(alpha + truth.yaw), truth * point, -1, Known::kLine), &plane,
          1.0e6};
}

RltPlane AnyWall() { return RltPlane(0, testing::SeenAlongX({2, -1}, {2, 1}, 0.0, 0), 0.05, 1000); }

TEST(GroupPlacement, TwoCrossingLinesFixTheWholePlacement) {
  const geometry::Pose2 truth{1.0, 2.0, 0.3};
  const RltPlane wall = AnyWall();
  const std::vector<GroupLink> links{LineLink(truth, 0.0, {0.0, 1.0}, wall),
                                     LineLink(truth, M_PI / 2.0, {3.0, 0.0}, wall)};
  Prior prior;
  prior.pose = {0.5, 1.5, 0.0};  // half a metre and 17 degrees off
  const geometry::Pose2 placed = SolveGroupPlacement(links, prior, MapperOptions{});
  EXPECT_NEAR(placed.yaw, truth.yaw, 1e-9);
  EXPECT_NEAR(placed.x, truth.x, 1e-3);
  EXPECT_NEAR(placed.y, truth.y, 1e-3);
}

TEST(GroupPlacement, AlongTheOnlyLineThePriorDecides) {
  // One wall, along the group's x axis: it fixes the rotation and the offset across it; where the
  // group lies along it is the prior's, not a guess from the line.
  const geometry::Pose2 truth{1.0, 2.0, 0.3};
  const RltPlane wall = AnyWall();
  const std::vector<GroupLink> links{LineLink(truth, 0.0, {0.0, 1.0}, wall)};
  Prior prior;
  prior.pose = {0.4, 2.5, truth.yaw};
  const geometry::Pose2 placed = SolveGroupPlacement(links, prior, MapperOptions{});
  const Vector2d along(std::cos(truth.yaw), std::sin(truth.yaw));
  const Vector2d across(-along.y(), along.x());
  const Vector2d error = Vector2d(placed.x, placed.y) - Vector2d(truth.x, truth.y);
  const Vector2d prior_error = Vector2d(prior.pose.x, prior.pose.y) - Vector2d(truth.x, truth.y);
  EXPECT_NEAR(across.dot(error), 0.0, 1e-3);
  EXPECT_NEAR(along.dot(error), along.dot(prior_error), 1e-3);
}

TEST(GroupPlacement, WithoutLinksThePriorStands) {
  Prior prior;
  prior.pose = {0.4, 2.5, 0.2};
  const geometry::Pose2 placed = SolveGroupPlacement({}, prior, MapperOptions{});
  EXPECT_DOUBLE_EQ(placed.x, 0.4);
  EXPECT_DOUBLE_EQ(placed.y, 2.5);
  EXPECT_DOUBLE_EQ(placed.yaw, 0.2);
}

}  // namespace
}  // namespace relplane::mapper
