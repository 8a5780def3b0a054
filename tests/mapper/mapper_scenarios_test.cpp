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

// Issue 5: a 3-lap loop with recesses; the motion model at every turn, a pose every frame, and
// the first lap's walls reused afterwards (loop closure, no duplicates).
std::vector<geometry::Pose2> LoopRoute(int laps) {
  return Drive({{0, 0}, {8, 0}, {8, 6}, {0, 6}}, 1.0, 0.8, 30.0, laps);
}

void ExpectLoop(const RunResult& r, double ate, double ends) {
  EXPECT_LE(r.ate_rmse, ate);
  EXPECT_LT(r.end_error, ends);
  EXPECT_LT(r.end_error_any, ends);
  EXPECT_LT(r.angle_error, 0.0175);
  EXPECT_EQ(r.duplicates, 0);
  EXPECT_EQ(r.lost, 0);
  EXPECT_GT(r.motion_model, 0);
}

TEST(MapperScenario, HallwayLoopNoiseFree) {
  ExpectLoop(RunWorld(HallwayLoop(10, 8, 2, 3), LoopRoute(3), {}), 0.01, 0.01);
}

TEST(MapperScenario, HallwayLoopNoisy) {
  ExpectLoop(RunWorld(HallwayLoop(10, 8, 2, 3), LoopRoute(3), Noisy()), 0.05, 0.05);
}

// Worlds and a sensor the defaults were never tuned on: narrower and shorter view, other sizes.
Frustum OtherSensor() { return {70.0 * M_PI / 180.0, 6.0, 1.4, 0.15}; }

TEST(MapperScenario, UnseenHallwayOtherSensor) {
  const auto poses = Drive({{0, 0}, {12, 0}}, 0.7, 0.8);
  ExpectNoisy(RunWorld(HallwayWithDoors(16.0, 2.6), poses, Noisy(11), OtherSensor()));
}

TEST(MapperScenario, UnseenLoopOtherSensor) {
  const auto poses = Drive({{0, 0}, {11, 0}, {11, 5}, {0, 5}}, 1.3, 0.6, 30.0, 2);
  ExpectLoop(RunWorld(HallwayLoop(13, 7, 2.4, 2.5), poses, Noisy(13), OtherSensor()), 0.05, 0.05);
}

}  // namespace
}  // namespace relplane::mapper::testing
