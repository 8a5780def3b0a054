// Straight legs and their along-track errors from hand-made frame poses with known answers.
#include "relplane/accuracy/legs.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace relplane::accuracy {
namespace {

FramePose Frame(int64_t seq, double true_x, double true_y, double true_yaw, double x, double y) {
  FramePose p;
  p.seq = seq;
  p.status = 0;
  p.true_x = true_x, p.true_y = true_y, p.true_yaw = true_yaw;
  p.x = x, p.y = y;
  return p;
}

// 10 m along +x measured 2 % short, a quarter turn in place, 5 m along +y measured exactly
// (the error it started with, 0.2 m along x, is across this leg and stays).
std::vector<FramePose> LShapedRun() {
  std::vector<FramePose> poses;
  int64_t seq = 0;
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.1 * i;
    poses.push_back(Frame(seq++, t, 0.0, 0.0, 0.98 * t, 0.0));
  }
  for (int i = 1; i <= 9; ++i) {
    poses.push_back(Frame(seq++, 10.0, 0.0, 0.5 * M_PI * i / 10.0, 9.8, 0.0));
  }
  for (int i = 0; i <= 50; ++i) {
    const double t = 0.1 * i;
    poses.push_back(Frame(seq++, 10.0, t, 0.5 * M_PI, 9.8, t));
  }
  return poses;
}

TEST(StraightLegs, EachLegsAlongErrorIsWhatItGainedFromItsFirstFrame) {
  const std::vector<Leg> legs = StraightLegs(LShapedRun());
  ASSERT_EQ(legs.size(), 2u);  // the turn's frames are each their own heading: no leg
  EXPECT_EQ(legs[0].first_seq, 0);
  EXPECT_EQ(legs[0].last_seq, 100);
  EXPECT_NEAR(legs[0].length_m, 10.0, 1e-9);
  EXPECT_NEAR(legs[0].along_error_m, -0.2, 1e-9);
  EXPECT_EQ(legs[1].first_seq, 110);
  EXPECT_NEAR(legs[1].length_m, 5.0, 1e-9);
  EXPECT_NEAR(legs[1].along_error_m, 0.0, 1e-9);
  EXPECT_NEAR(AlongTrackPercent(legs), 100.0 * -0.2 / 15.0, 1e-9);
}

TEST(StraightLegs, AFrameWithoutAPoseNeitherEndsALegNorIsMeasured) {
  std::vector<FramePose> poses = LShapedRun();
  poses[100].status = -1;  // the first leg's last frame was refused
  poses[100].x = 1e6;
  poses[50].status = -1;
  const std::vector<Leg> legs = StraightLegs(poses);
  ASSERT_EQ(legs.size(), 2u);
  EXPECT_EQ(legs[0].last_seq, 99);
  EXPECT_NEAR(legs[0].along_error_m, -0.02 * 9.9, 1e-9);
}

TEST(StraightLegs, ShortLegsAreLeftOutAndNoLegsIsZeroPercent) {
  EXPECT_EQ(StraightLegs(LShapedRun(), 20.0).size(), 0u);
  EXPECT_EQ(StraightLegs(LShapedRun(), 6.0).size(), 1u);
  EXPECT_EQ(AlongTrackPercent({}), 0.0);
}

}  // namespace
}  // namespace relplane::accuracy
