// DominantLineFit (dominant_line.hpp) on a pilaster's front seen at a grazing angle, sampled as a
// depth sensor samples it: columns of rays, noise along each ray.

#include "relplane/segmenter/dominant_line.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "plane_fit_testing.hpp"

namespace relplane::segmenter {
namespace {

using testing::ErrorDeg;
using testing::LeastSquares;

constexpr double kDeg = 180.0 / M_PI;
constexpr double kSigma = 0.01;  // m, along each ray

// In the sensor frame (x ahead, y left, z up): the front, y = 0.95 for x in [3.84, 4.22], faces
// the sensor at a grazing angle; the side, x = 3.84 for y in [0.95, 1.25], square on. Rays every
// 0.35 degrees both ways (loop_other_sensor's 70 degrees over 200 columns), z from -1 to 1 m.
// Returns the front's samples, then the side's within `side_depth` of the corner: what EM gave
// the front's piece on loop_other_sensor seed 41 (a column or two of the side).
std::vector<Eigen::Vector3f> GrazingFront(double side_depth, size_t* front_count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  constexpr double kStep = 0.35 / kDeg;
  std::vector<Eigen::Vector3f> front, side;
  for (double bearing = 0.2; bearing < 0.35; bearing += kStep) {
    const Eigen::Vector2d ray(std::cos(bearing), std::sin(bearing));
    // The nearer of the two faces the ray meets.
    double t = 0.95 / ray.y();
    bool on_front = ray.x() * t >= 3.84 && ray.x() * t <= 4.22;
    if (!on_front) {
      t = 3.84 / ray.x();
      if (ray.y() * t < 0.95 || ray.y() * t > 0.95 + side_depth) continue;
    }
    for (double elevation = -0.25; elevation < 0.25; elevation += kStep) {
      const Eigen::Vector3d dir = Eigen::Vector3d(ray.x(), ray.y(), std::tan(elevation));
      const Eigen::Vector3d unit = dir.normalized();
      const Eigen::Vector3d hit = t * dir;
      if (std::abs(hit.z()) > 1.0) continue;
      const Eigen::Vector3d p = hit + kSigma * noise(rng) * unit;
      (on_front ? front : side).push_back(p.cast<float>());
    }
  }
  *front_count = front.size();
  front.insert(front.end(), side.begin(), side.end());
  return front;
}

// The trim a piece gets from the noise expected along the front's normal: 2.5 sigma of
// 1 cm x |n.d| (0.24 here), at least the segmenter's sigma_min of 3 mm.
constexpr double kTrim = 2.5 * 0.003;

PlaneFit Dominant(const std::vector<Eigen::Vector3f>& points, const PlaneFit& start,
                  double min_share = 0.5) {
  return DominantLineFit(points.data(), points.size(), Eigen::Vector3d::Zero(), start, kTrim, 2.5f,
                         0.003f, 10, min_share);
}

TEST(DominantLineFit, AGrazingFrontLeavesTheSidesColumnsAtTheCornerOut) {
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE(seed);
    size_t front = 0;
    const std::vector<Eigen::Vector3f> points = GrazingFront(0.05, &front, seed);
    ASSERT_GT(points.size(), front + 100) << "the side's columns are part of the piece";
    const PlaneFit start = LeastSquares(points);
    // The problem: the fit leans between the faces, and trimming at its RMS keeps the side.
    const PlaneFit trimmed = IterateTrimmedFit(points.data(), points.size(),
                                               Eigen::Vector3d::Zero(), start, 2.5f, 0.003f, 10);
    EXPECT_GT(ErrorDeg(trimmed), 2.0);
    const PlaneFit line = Dominant(points, trimmed);
    EXPECT_GT(line.fits, 0);
    EXPECT_LT(ErrorDeg(line), 0.5);
    EXPECT_NEAR(line.centroid.y(), 0.95, 0.005);
    EXPECT_GE(line.count, 0.9 * front);
    // The side's samples beyond the front's noise stay out: about the front's own RMS is left
    // (1 cm x |n.d| of 0.22-0.26), not the leaning fit's.
    EXPECT_GT(trimmed.rms, 0.008);
    EXPECT_LT(line.rms, 0.003);
  }
}

TEST(DominantLineFit, AFrontSeenAloneKeepsItsFit) {
  size_t front = 0;
  const std::vector<Eigen::Vector3f> points = GrazingFront(0.0, &front, 7);
  ASSERT_EQ(points.size(), front);
  const PlaneFit start = LeastSquares(points);
  const PlaneFit line = Dominant(points, start);
  EXPECT_GT(line.fits, 0);
  EXPECT_LT(std::abs(ErrorDeg(line) - ErrorDeg(start)), 0.1);
  EXPECT_GE(line.count, 0.97 * front);
}

TEST(DominantLineFit, NoLineHoldingEnoughOfThePointsLeavesTheStart) {
  size_t front = 0;
  const std::vector<Eigen::Vector3f> points = GrazingFront(0.05, &front, 3);
  const PlaneFit start = LeastSquares(points);
  // The front holds fewer than 99 % of the piece's points: nothing changes.
  const PlaneFit line = Dominant(points, start, 0.99);
  EXPECT_EQ(line.fits, 0);
  EXPECT_EQ(line.normal, start.normal);
  EXPECT_EQ(line.count, start.count);
}

TEST(DominantLineFit, TooFewPointsOrANonWallLeaveTheStart) {
  size_t front = 0;
  const std::vector<Eigen::Vector3f> points = GrazingFront(0.05, &front, 4);
  const PlaneFit start = LeastSquares(points);
  EXPECT_EQ(DominantLineFit(points.data(), 10, Eigen::Vector3d::Zero(), start, kTrim, 2.5f, 0.003f,
                            10, 0.5)
                .fits,
            0);
  PlaneFit floor = start;
  floor.normal = Eigen::Vector3d::UnitZ();
  EXPECT_EQ(Dominant(points, floor).fits, 0);
}

}  // namespace
}  // namespace relplane::segmenter
