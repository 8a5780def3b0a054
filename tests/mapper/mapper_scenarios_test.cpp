// End-to-end accuracy of the mapper on ideal-segmenter worlds (issue 4 and 5 targets), with
// default options throughout.
#include <gtest/gtest.h>

#include "ideal_segmenter.hpp"

namespace relplane::mapper::testing {
namespace {

using Eigen::Vector2d;

// Plane-level noise of the order a segmenter gives for sigma = 1 cm points: plane fits over
// thousands of points are good to millimetres, the extreme points along a wall to ~1.5 cm.
Noise Noisy(uint64_t seed = 7) { return {0.003, 0.003, 0.015, seed}; }

RunResult RunWorld(const World& world, const std::vector<geometry::Pose2>& poses, Noise noise,
                   Frustum frustum = {}) {
  IdealSegmenter segmenter(world, frustum, noise);
  Mapper mapper;
  RunResult r = Run(mapper, segmenter, poses);
  std::printf("%s%s: %s\n", world.name.c_str(), noise.edge > 0 ? " (noisy)" : "",
              Describe(r).c_str());
  return r;
}

std::vector<geometry::Pose2> OfficeRoute() {
  return Drive({{0, 0}, {6, 0}, {6, -1.5}, {6, 0}, {0, 0}, {0, 5}, {0, 0}}, 1.0, 0.8);
}

void ExpectNoiseFree(const RunResult& r) {
  EXPECT_LT(r.ate_rmse, 0.01);
  EXPECT_LT(r.end_error, 0.01);
  EXPECT_LT(r.end_error_any, 0.01);
  EXPECT_LT(r.angle_error, 0.0175);
  EXPECT_EQ(r.duplicates, 0);
  EXPECT_EQ(r.unmatched, 0);
  EXPECT_EQ(r.lost, 0);
}

void ExpectNoisy(const RunResult& r) {
  EXPECT_LE(r.ate_rmse, 0.05);
  EXPECT_LT(r.end_error, 0.05);
  EXPECT_LT(r.end_error_any, 0.05);
  EXPECT_LT(r.angle_error, 0.0175);
  EXPECT_EQ(r.duplicates, 0);
  EXPECT_EQ(r.unmatched, 0);
  EXPECT_EQ(r.lost, 0);
}

TEST(MapperScenario, StraightHallwayNoiseFree) {
  ExpectNoiseFree(RunWorld(StraightHallway(), Drive({{0, 0}, {5, 0}}, 1.0, 0.8), {}));
}

TEST(MapperScenario, StraightHallwayNoisy) {
  ExpectNoisy(RunWorld(StraightHallway(), Drive({{0, 0}, {5, 0}}, 1.0, 0.8), Noisy()));
}

TEST(MapperScenario, HallwayWithDoorsNoiseFree) {
  ExpectNoiseFree(RunWorld(HallwayWithDoors(), Drive({{0, 0}, {10, 0}}, 1.0, 0.8), {}));
}

TEST(MapperScenario, HallwayWithDoorsNoisy) {
  ExpectNoisy(RunWorld(HallwayWithDoors(), Drive({{0, 0}, {10, 0}}, 1.0, 0.8), Noisy()));
}

TEST(MapperScenario, OfficeNoiseFree) { ExpectNoiseFree(RunWorld(Office(), OfficeRoute(), {})); }

TEST(MapperScenario, OfficeNoisy) { ExpectNoisy(RunWorld(Office(), OfficeRoute(), Noisy())); }

}  // namespace
}  // namespace relplane::mapper::testing
