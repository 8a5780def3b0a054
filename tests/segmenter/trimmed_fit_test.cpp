// IterateTrimmedFit (trimmed_fit.hpp) against planes whose truth is known.

#include "relplane/segmenter/trimmed_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "plane_fit_testing.hpp"

namespace relplane::segmenter {
namespace {

using testing::ErrorDeg;
using testing::LeastSquares;

// A 0.4 m face in the plane y = 0 (x from 0 to 0.4, z from 0 to 2), its samples spread
// `sigma` along its normal; with `corner_points`, samples of a crossing face at x = 0 running
// 0-8 cm behind it (y from 0 to 0.08), 1 cm noise across that face: what a grazing face's
// piece takes from the face it meets at a convex corner.
std::vector<Eigen::Vector3f> Face(double sigma, int corner_points, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> along(0.0, 1.0);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 2000; ++i) {
    points.emplace_back(0.4 * along(rng), sigma * noise(rng), 2.0 * along(rng));
  }
  for (int i = 0; i < corner_points; ++i) {
    points.emplace_back(0.01 * noise(rng), 0.08 * along(rng), 2.0 * along(rng));
  }
  return points;
}

TEST(IterateTrimmedFit, ACrossingFacesPointsDropOutOfAGrazingFacesFit) {
  // 300 of 2,300 points from the crossing face: the plain fit leans by degrees.
  const std::vector<Eigen::Vector3f> points = Face(0.003, 300, 1);
  const PlaneFit plain = LeastSquares(points);
  ASSERT_GT(ErrorDeg(plain), 3.0);
  const PlaneFit fit = IterateTrimmedFit(points.data(), points.size(), Eigen::Vector3d::Zero(),
                                         plain, 2.5f, 0.003f, 10);
  EXPECT_GE(fit.fits, 2);
  EXPECT_LT(ErrorDeg(fit), 0.3);
  EXPECT_LT(std::fabs(fit.centroid.y()), 0.005);
  // The face's own points stay in: about 2,000 of them, and few of the crossing face's.
  EXPECT_GT(fit.count, 1950);
  EXPECT_LT(fit.count, 2100);
  EXPECT_LT(fit.rms, 0.005);
}

TEST(IterateTrimmedFit, OneTrimAtTheLeaningFitsRmsKeepsMostOfThem) {
  // What a piece's fit was before: one trim at 2.5 of the first fit's RMS.
  const std::vector<Eigen::Vector3f> points = Face(0.003, 300, 1);
  const PlaneFit plain = LeastSquares(points);
  const PlaneFit once = IterateTrimmedFit(points.data(), points.size(), Eigen::Vector3d::Zero(),
                                          plain, 2.5f, 0.003f, 1);
  EXPECT_EQ(once.fits, 1);
  EXPECT_GT(ErrorDeg(once), 1.0);
}

TEST(IterateTrimmedFit, ACleanPlaneKeepsItsPointsAndItsNoise) {
  // Cutting a Gaussian at 2.5 sigma leaves 95.5 % of its RMS; taken as the noise, each trim
  // would close in on the plane. Scaled back, the trim stays at 2.5 sigma.
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    const std::vector<Eigen::Vector3f> points = Face(0.01, 0, seed);
    const PlaneFit plain = LeastSquares(points);
    const PlaneFit fit = IterateTrimmedFit(points.data(), points.size(), Eigen::Vector3d::Zero(),
                                           plain, 2.5f, 0.003f, 10);
    EXPECT_LE(fit.fits, 3);
    EXPECT_GT(fit.count, 0.98 * points.size());  // 98.8 % lie within 2.5 sigma
    EXPECT_NEAR(fit.rms, 0.0095, 0.0006);
    EXPECT_LT(ErrorDeg(fit), 0.3);
  }
}

TEST(IterateTrimmedFit, FewerThanThreePointsLeaveTheStart) {
  const std::vector<Eigen::Vector3f> points = {{0, 0, 0}, {1, 0, 0}};
  PlaneFit start;
  start.normal = Eigen::Vector3d(0, -1, 0);
  start.count = 7;
  const PlaneFit fit = IterateTrimmedFit(points.data(), points.size(), Eigen::Vector3d::Zero(),
                                         start, 2.5f, 0.003f, 10);
  EXPECT_EQ(fit.fits, 0);
  EXPECT_EQ(fit.count, 7);
  EXPECT_EQ(fit.normal, start.normal);
}

// Two parallel faces 4 cm apart, 1 cm noise across each, the fit started on the nearer one's
// points within 2 cm: each trim at 2.5 sigma of the fit's RMS takes in more of the other face,
// and the fit walks over towards it. Capped at 2 cm (max_trim) it stays on the first face: how
// DominantLineFit keeps to the line it chose (a door recess's wall and back wall at a corner
// otherwise grew back into one fit, and the recess's jamb went into it).
TEST(IterateTrimmedFit, ACappedTrimStaysOnTheFaceItStartedOn) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::uniform_real_distribution<double> along(0.0, 1.0);
  std::vector<Eigen::Vector3f> points, near;
  for (int i = 0; i < 4000; ++i) {
    const double y = (i % 2 ? 0.04 : 0.0) + noise(rng);
    points.emplace_back(along(rng), y, 2.0 * along(rng));
    if (std::abs(y) < 0.02) near.push_back(points.back());
  }
  const PlaneFit start = LeastSquares(near);
  const PlaneFit free = IterateTrimmedFit(points.data(), points.size(), Eigen::Vector3d::Zero(),
                                          start, 2.5f, 0.003f, 10);
  const PlaneFit capped = IterateTrimmedFit(points.data(), points.size(), Eigen::Vector3d::Zero(),
                                            start, 2.5f, 0.003f, 10, 0.02);
  EXPECT_GT(free.centroid.y(), 0.01) << "the free trim no longer walks";
  EXPECT_LT(std::abs(capped.centroid.y()), 0.006);
  EXPECT_LT(capped.count, free.count);
}

}  // namespace
}  // namespace relplane::segmenter
