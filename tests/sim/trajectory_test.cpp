// Trajectory: speed, turn rate, laps, drive-back, smooth turns, and fixed sampling.

#include "relplane/sim/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "angles.hpp"

namespace relplane::sim {
namespace {

using testing::kPi;

TrajectoryOptions Square(double side) {
  TrajectoryOptions o;
  o.waypoints = {{0, 0}, {side, 0}, {side, side}, {0, side}};
  o.closed = true;
  return o;
}

double Distance(const geometry::Pose2& a, const geometry::Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

TEST(Trajectory, StraightLineAtConstantSpeed) {
  TrajectoryOptions o;
  o.waypoints = {{0, 0}, {10, 0}};
  o.speed = 2.0;
  const Trajectory t(o);
  EXPECT_DOUBLE_EQ(t.Duration(), 5.0);
  const double dt = 1.0 / 30.0;
  ASSERT_EQ(t.NumSamples(dt), 151);
  for (int64_t k = 1; k < t.NumSamples(dt); ++k) {
    EXPECT_NEAR(Distance(t.Sample(k, dt), t.Sample(k - 1, dt)), 2.0 * dt, 1e-9);
    EXPECT_EQ(t.Sample(k, dt).yaw, 0.0);
  }
  const geometry::Pose2 end = t.Sample(150, dt);
  EXPECT_NEAR(end.x, 10.0, 1e-9);
}

TEST(Trajectory, TurnsInPlaceAtTheTurnRate) {
  TrajectoryOptions o;
  o.waypoints = {{0, 0}, {4, 0}, {4, 4}};
  o.speed = 1.0;
  o.turn_rate = 0.5;
  const Trajectory t(o);
  EXPECT_NEAR(t.Duration(), 8.0 + (kPi / 2) / 0.5, 1e-12);
  const double dt = 0.01;
  for (double time = 4.0 + dt; time < 4.0 + kPi - dt; time += dt) {
    const geometry::Pose2 p = t.At(time);
    EXPECT_NEAR(p.x, 4.0, 1e-12);
    EXPECT_NEAR(p.y, 0.0, 1e-12);
    EXPECT_NEAR(p.yaw, 0.5 * (time - 4.0), 1e-9);
  }
  const geometry::Pose2 end = t.At(t.Duration());
  EXPECT_NEAR(end.x, 4.0, 1e-12);
  EXPECT_NEAR(end.y, 4.0, 1e-12);
  EXPECT_NEAR(end.yaw, kPi / 2, 1e-12);
}

TEST(Trajectory, FirstTurnsTowardsTheFirstSegment) {
  TrajectoryOptions o;
  o.waypoints = {{0, 0}, {0, 5}};
  o.turn_rate = 1.0;
  const Trajectory t(o);
  EXPECT_EQ(t.At(0.0).yaw, 0.0) << "every scenario starts heading +x";
  EXPECT_NEAR(t.Duration(), kPi / 2 + 5.0, 1e-12);
  EXPECT_NEAR(t.At(t.Duration()).y, 5.0, 1e-12);
}

TEST(Trajectory, LapsGoRoundAndEndAtTheStart) {
  TrajectoryOptions o = Square(4.0);
  o.laps = 2;
  o.turn_rate = 1.0;
  const Trajectory t(o);
  // 2 x 16 m, turns at three corners per lap plus one at the start of lap 2.
  EXPECT_NEAR(t.Duration(), 32.0 + 7 * (kPi / 2), 1e-9);
  const geometry::Pose2 end = t.At(t.Duration());
  EXPECT_NEAR(end.x, 0.0, 1e-9);
  EXPECT_NEAR(end.y, 0.0, 1e-9);
  EXPECT_NEAR(end.yaw, -kPi / 2, 1e-9);
  // Halfway (end of lap 1, before the turn) the robot is back at the start as well.
  const double lap = 16.0 + 3 * (kPi / 2);
  EXPECT_NEAR(t.At(lap).x, 0.0, 1e-9);
  EXPECT_NEAR(t.At(lap).y, 0.0, 1e-9);
  EXPECT_NEAR(t.At(lap - 1.0).y, 1.0, 1e-9);
}

TEST(Trajectory, DriveBackRetracesThePath) {
  TrajectoryOptions o;
  o.waypoints = {{0, 0}, {5, 0}, {5, 3}};
  o.drive_back = true;
  o.turn_rate = 1.0;
  const Trajectory t(o);
  EXPECT_NEAR(t.Duration(), 8.0 + kPi / 2 + kPi + kPi / 2 + 8.0, 1e-9);
  const geometry::Pose2 end = t.At(t.Duration());
  EXPECT_NEAR(end.x, 0.0, 1e-9);
  EXPECT_NEAR(end.y, 0.0, 1e-9);
  EXPECT_NEAR(std::abs(end.yaw), kPi, 1e-9);
  // On the way back it passes the same points, facing the other way.
  const geometry::Pose2 out = t.At(2.0);
  const geometry::Pose2 back = t.At(t.Duration() - 2.0);
  EXPECT_NEAR(Distance(out, back), 0.0, 1e-9);
  EXPECT_NEAR(std::abs(geometry::WrapAngle(out.yaw - back.yaw)), kPi, 1e-9);
}

TEST(Trajectory, SmoothTurnsKeepSpeedAndTurnRate) {
  TrajectoryOptions o = Square(8.0);
  o.turn = TurnMode::kSmooth;
  o.speed = 1.0;
  o.turn_rate = 0.5;  // radius 2 m
  const Trajectory t(o);
  const double dt = 1.0 / 30.0;
  double closest_to_corner = 1e9;
  for (int64_t k = 1; k < t.NumSamples(dt); ++k) {
    const geometry::Pose2 a = t.Sample(k - 1, dt);
    const geometry::Pose2 b = t.Sample(k, dt);
    const double step = Distance(a, b);
    // Arcs move along chords slightly shorter than the arc length.
    EXPECT_LE(step, 1.0 * dt + 1e-9);
    EXPECT_GE(step, 1.0 * dt * 0.999);
    EXPECT_LE(std::abs(geometry::WrapAngle(b.yaw - a.yaw)), 0.5 * dt + 1e-9);
    closest_to_corner = std::min(closest_to_corner, std::hypot(b.x - 8.0, b.y));
  }
  // A 90° arc of radius r passes the corner at r (sqrt 2 - 1).
  EXPECT_NEAR(closest_to_corner, 2.0 * (std::sqrt(2.0) - 1.0), 0.01);
  const double expected = 4 * (8.0 - 4.0) + 3 * (2.0 * kPi / 2) + 4.0;
  EXPECT_NEAR(t.Duration(), expected, 1e-9) << "three arcs; the closing corner is the end";
}

TEST(Trajectory, SmoothFallsBackToInPlaceWhenTheArcDoesNotFit) {
  TrajectoryOptions o = Square(2.0);
  o.turn = TurnMode::kSmooth;
  o.speed = 1.0;
  o.turn_rate = 0.5;  // a 2 m radius needs 2 m of each 2 m side: too much
  const Trajectory t(o);
  EXPECT_NEAR(t.Duration(), 8.0 + 3 * (kPi / 2) / 0.5, 1e-9);
}

TEST(Trajectory, RejectsImpossibleOptions) {
  TrajectoryOptions o;
  o.waypoints = {{1, 1}};
  EXPECT_THROW(Trajectory{o}, std::invalid_argument);
  o.waypoints = {{1, 1}, {1, 1}};
  EXPECT_THROW(Trajectory{o}, std::invalid_argument);
  o = TrajectoryOptions{};
  o.speed = 0.0;
  EXPECT_THROW(Trajectory{o}, std::invalid_argument);
  o = TrajectoryOptions{};
  o.laps = 2;
  EXPECT_THROW(Trajectory{o}, std::invalid_argument);
}

}  // namespace
}  // namespace relplane::sim
