// PCL's segmentations through relplane-compare's adapter: a floor and a wall rendered into an
// organized frame in relplane's sensor frame come back as the same two planes, in the sensor
// frame, facing the sensor (the adapter turns frames to PCL's optical frame and planes back).

#include "relplane/compare/pcl_segmenters.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "relplane/compare/detections.hpp"

namespace relplane::compare {
namespace {

constexpr int kWidth = 160, kHeight = 120;
constexpr float kFocal = 150.0f;  // pixels

// A pinhole camera at the origin looking along x at the floor z = -1 and the wall x = 5; the
// top-left pixels of the image see nothing (NaN), as a camera beyond its range.
OrganizedFrame FloorAndWall() {
  OrganizedFrame frame;
  frame.width = kWidth;
  frame.height = kHeight;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 0; v < kHeight; ++v) {
    for (int u = 0; u < kWidth; ++u) {
      const Eigen::Vector3f ray(1.0f, -(u - kWidth / 2.0f) / kFocal,
                                -(v - kHeight / 2.0f) / kFocal);
      float t = 5.0f;  // the wall
      if (ray.z() < 0.0f) t = std::min(t, -1.0f / ray.z());
      if (u < 10 && v < 10) {
        frame.points.Add(nan, nan, nan);
      } else {
        frame.points.Add(ray * t);
      }
    }
  }
  return frame;
}

void ExpectFloorAndWall(const Detections& found) {
  ASSERT_EQ(found.planes.size(), 2u);
  ASSERT_EQ(found.labels.size(), static_cast<size_t>(kWidth * kHeight));
  bool floor = false, wall = false;
  for (const segmenter::DetectedPlane& p : found.planes) {
    EXPECT_GE(p.d, 0.0f);
    EXPECT_GE(p.num_points, 300);
    if (p.normal.z() > 0.999f) {
      floor = true;
      EXPECT_NEAR(p.d, 1.0f, 0.01f);
    }
    if (p.normal.x() < -0.999f) {
      wall = true;
      EXPECT_NEAR(p.d, 5.0f, 0.01f);
    }
  }
  EXPECT_TRUE(floor);
  EXPECT_TRUE(wall);
  EXPECT_EQ(found.labels.front(), -1);  // a NaN pixel
}

TEST(PclSegmenters, OrganizedFindsFloorAndWallInTheSensorFrame) {
  const OrganizedFrame frame = FloorAndWall();
  ExpectFloorAndWall(Describe(frame.points, SegmentOrganized(frame, OrganizedParams{}).planes));
}

TEST(PclSegmenters, SacFindsFloorAndWallInTheSensorFrame) {
  const OrganizedFrame frame = FloorAndWall();
  ExpectFloorAndWall(Describe(frame.points, SegmentSac(frame, SacParams{}).planes));
}

TEST(PclSegmenters, SacRepeatsItself) {
  const OrganizedFrame frame = FloorAndWall();
  const PclResult a = SegmentSac(frame, SacParams{}), b = SegmentSac(frame, SacParams{});
  ASSERT_EQ(a.planes.size(), b.planes.size());
  for (size_t i = 0; i < a.planes.size(); ++i) EXPECT_EQ(a.planes[i].indices, b.planes[i].indices);
}

}  // namespace
}  // namespace relplane::compare
