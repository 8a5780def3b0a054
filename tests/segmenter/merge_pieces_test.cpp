// MergeTouchingPieces on hand-made pieces: which pairs of vertical pieces are one surface.

#include "relplane/segmenter/merge_pieces.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace relplane::segmenter {
namespace {

// A vertical piece `width` wide and 1.8 m high, centred on (x, y) at the sensor's height,
// facing the sensor at the origin turned by `yaw_deg` about the vertical: its points on a 2 cm
// grid, their scatter and rays, and the rectangle around them.
PieceStats Piece(float x, float y, float width, float yaw_deg) {
  const float yaw = yaw_deg * static_cast<float>(M_PI) / 180.0f;
  const Eigen::Vector3f normal(-std::cos(yaw), -std::sin(yaw), 0.0f);  // towards the origin
  const Eigen::Vector3f along = Eigen::Vector3f::UnitZ().cross(normal).normalized();
  const Eigen::Vector3f centre(x, y, 0.0f);
  std::vector<Eigen::Vector3f> points;
  for (float s = -0.5f * width; s <= 0.5f * width + 1e-4f; s += 0.02f) {
    for (float z = -0.9f; z <= 0.9f + 1e-4f; z += 0.02f) {
      points.push_back(centre + s * along + z * Eigen::Vector3f::UnitZ());
    }
  }
  PieceStats p;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& q : points) mean += q.cast<double>();
  mean /= static_cast<double>(points.size());
  for (const auto& q : points) {
    const Eigen::Vector3d d = q.cast<double>() - mean;
    p.scatter += d * d.transpose();
    const Eigen::Vector3d ray = q.cast<double>().normalized();
    p.rays += ray * ray.transpose();
  }
  p.vertical = true;
  p.plane.normal = normal;
  p.plane.d = -normal.dot(mean.cast<float>());
  p.plane.centroid = mean.cast<float>();
  p.plane.num_points = static_cast<int>(points.size());
  const float h = 0.5f * width;
  p.plane.vertices = {centre - h * along - 0.9f * Eigen::Vector3f::UnitZ(),
                      centre + h * along - 0.9f * Eigen::Vector3f::UnitZ(),
                      centre + h * along + 0.9f * Eigen::Vector3f::UnitZ(),
                      centre - h * along + 0.9f * Eigen::Vector3f::UnitZ()};
  return p;
}

size_t Merged(const PieceStats& a, const PieceStats& b) {
  return MergeTouchingPieces({a, b}, Options{}, nullptr).size();
}

TEST(MergePieces, AFaceFittedAsTwoPlanesNineDegreesApartIsOne) {
  // One 0.3 m face 2 m ahead, its points split between two fits turned 4.5 degrees each way
  // (loop_other_sensor at 1 cm: a pilaster's side).
  const std::vector<PieceStats> merged = MergeTouchingPieces(
      {Piece(2.0f, 1.1f, 0.3f, 4.5f), Piece(2.0f, 1.1f, 0.3f, -4.5f)}, Options{}, nullptr);
  ASSERT_EQ(merged.size(), 1u);
  // The pooled fit faces the sensor square on, as the face does.
  EXPECT_LT(std::abs(merged[0].plane.normal.y()), 0.02f);
  EXPECT_NEAR(merged[0].plane.normal.x(), -1.0f, 1e-3f);
}

TEST(MergePieces, PiecesOverEachOtherBeyondTheAngleStayApart) {
  Options options;
  EXPECT_EQ(Merged(Piece(2.0f, 1.1f, 0.3f, 0.5f * options.merge.overlap_angle_deg + 1.0f),
                   Piece(2.0f, 1.1f, 0.3f, -0.5f * options.merge.overlap_angle_deg - 1.0f)),
            2u);
}

TEST(MergePieces, AFaceBeforeTheWallBehindItStaysApart) {
  // A pilaster's front 0.3 m before the wall it stands out of: over each other in the view,
  // but neither centroid lies in the other's plane.
  EXPECT_EQ(Merged(Piece(2.0f, 0.0f, 0.4f, 0.0f), Piece(2.3f, 0.0f, 2.0f, 0.0f)), 2u);
}

TEST(MergePieces, TouchingPiecesSideBySideStillNeedTheNarrowAngle) {
  // Two halves of a face side by side, 9 degrees apart: they touch but do not lie over each
  // other, so piece_merge_angle_deg (6 degrees) decides, as before.
  EXPECT_EQ(Merged(Piece(2.0f, 1.0f, 0.2f, 4.5f), Piece(2.0f, 1.2f, 0.2f, -4.5f)), 2u);
  EXPECT_EQ(Merged(Piece(2.0f, 1.0f, 0.2f, 1.0f), Piece(2.0f, 1.2f, 0.2f, -1.0f)), 1u);
}

}  // namespace
}  // namespace relplane::segmenter
