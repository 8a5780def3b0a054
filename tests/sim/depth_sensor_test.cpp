// The sensor's noise, dropout and reproducibility.

#include "relplane/sim/depth_sensor.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "relplane/sim/world.hpp"

namespace relplane::sim {
namespace {

World Hallway() {
  WorldOptions options;
  options.generators = {StraightHallwayParams{}};
  return BuildWorld(options);
}

const geometry::Pose2 kPose{2.0, 0.2, 0.3};

TEST(DepthSensor, NoiseFreePointsLieOnTheirRectangles) {
  const World world = Hallway();
  DepthSensor sensor(world, SensorOptions{});
  const Scan scan = sensor.Capture(kPose, 0);
  ASSERT_GT(scan.points.size(), 10000u);
  const Eigen::Isometry3d pose = geometry::ToIsometry(kPose, 1.0);
  for (size_t i = 0; i < scan.points.size(); ++i) {
    const Eigen::Vector3d p = pose * scan.points[i].cast<double>();
    const Rect& r = world.rects[scan.rects[i]];
    EXPECT_NEAR(r.Normal().dot(p) + r.D(), 0.0, 1e-5);
    EXPECT_LE(scan.points[i].norm(), 8.0f + 1e-5f);
  }
}

TEST(DepthSensor, RangeNoiseHasTheConfiguredSigma) {
  const World world = Hallway();
  SensorOptions options;
  options.noise_sigma = 0.01;
  DepthSensor sensor(world, options);
  const std::vector<Hit> truth = sensor.CastTrue(kPose);
  const Scan scan = sensor.Capture(kPose, 3);
  // Without dropout every hit comes back, in ray order.
  std::vector<double> residuals;
  size_t j = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    if (truth[i].rect < 0) continue;
    ASSERT_LT(j, scan.points.size());
    const Eigen::Vector3d p = scan.points[j].cast<double>();
    // Noise is along the ray: the point stays on its ray.
    EXPECT_NEAR(p.normalized().dot(sensor.Grid().directions[i]), 1.0, 1e-6);
    residuals.push_back(p.norm() - truth[i].range);
    ++j;
  }
  ASSERT_EQ(j, scan.points.size());
  const double n = static_cast<double>(residuals.size());
  double mean = 0.0;
  for (double r : residuals) mean += r / n;
  double var = 0.0;
  for (double r : residuals) var += (r - mean) * (r - mean) / (n - 1);
  EXPECT_NEAR(mean, 0.0, 4 * 0.01 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(var), 0.01, 0.0005);
}

TEST(DepthSensor, DropoutRemovesTheConfiguredFraction) {
  const World world = Hallway();
  SensorOptions options;
  options.dropout = 0.3;
  DepthSensor sensor(world, options);
  size_t hits = 0;
  for (const Hit& h : sensor.CastTrue(kPose)) hits += h.rect >= 0 ? 1 : 0;
  const Scan scan = sensor.Capture(kPose, 0);
  const double kept = static_cast<double>(scan.points.size()) / static_cast<double>(hits);
  const double sd = std::sqrt(0.3 * 0.7 / static_cast<double>(hits));
  EXPECT_NEAR(kept, 0.7, 4 * sd);
}

TEST(DepthSensor, FixedSeedReproducesFrames) {
  const World world = Hallway();
  SensorOptions options;
  options.noise_sigma = 0.02;
  options.dropout = 0.1;
  DepthSensor a(world, options);
  DepthSensor b(world, options);
  // Frames in a different order: a frame depends only on (seed, frame, pose).
  a.Capture(kPose, 1);
  const Scan a5 = a.Capture(kPose, 5);
  const Scan b5 = b.Capture(kPose, 5);
  ASSERT_EQ(a5.points.size(), b5.points.size());
  for (size_t i = 0; i < a5.points.size(); ++i) ASSERT_EQ(a5.points[i], b5.points[i]);

  const Scan a6 = a.Capture(kPose, 6);
  options.seed = 2;
  DepthSensor c(world, options);
  const Scan c5 = c.Capture(kPose, 5);
  auto differs = [](const Scan& x, const Scan& y) {
    if (x.points.size() != y.points.size()) return true;
    for (size_t i = 0; i < x.points.size(); ++i) {
      if (x.points[i] != y.points[i]) return true;
    }
    return false;
  };
  EXPECT_TRUE(differs(a5, a6)) << "another frame draws other noise";
  EXPECT_TRUE(differs(a5, c5)) << "another seed draws other noise";
}

}  // namespace
}  // namespace relplane::sim
