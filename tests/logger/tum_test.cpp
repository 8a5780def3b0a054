// TUM trajectory text: round trip and malformed input.
#include "relplane/eval/tum.hpp"

#include <gtest/gtest.h>

#include <random>

#include "fixtures.hpp"

namespace relplane::eval {
namespace {

TEST(Tum, RoundTripKeepsTimesPositionsAndOrientations) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  std::vector<PoseSample> poses;
  for (int i = 0; i < 20; ++i) {
    PoseSample p = testing::Pose(i, u(rng), u(rng), u(rng));
    p.utime = 1234567 + 33333 * i;  // not a whole number of milliseconds
    p.position.z() = u(rng);
    poses.push_back(p);
  }
  const std::string text = FormatTum(poses);
  std::vector<PoseSample> back;
  std::string reason;
  ASSERT_TRUE(ParseTum(text, &back, &reason)) << reason;
  ASSERT_EQ(back.size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(back[i].utime, poses[i].utime);
    EXPECT_LT((back[i].position - poses[i].position).norm(), 1e-6);
    EXPECT_NEAR(std::abs(back[i].orientation.dot(poses[i].orientation)), 1.0, 1e-9);
  }
}

TEST(Tum, LinesAreTimeThenPositionThenQuaternionXyzw) {
  PoseSample p = testing::Pose(0, 1.0, 2.0, M_PI / 2);
  p.utime = 1500000;
  const std::string line = FormatTum({p});
  double v[8];
  ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3],
                        &v[4], &v[5], &v[6], &v[7]),
            8);
  EXPECT_DOUBLE_EQ(v[0], 1.5);
  EXPECT_DOUBLE_EQ(v[1], 1.0);
  EXPECT_DOUBLE_EQ(v[2], 2.0);
  EXPECT_NEAR(v[6], std::sqrt(0.5), 1e-9);  // qz
  EXPECT_NEAR(v[7], std::sqrt(0.5), 1e-9);  // qw last
}

TEST(Tum, CommentsAndBlankLinesAreSkippedAndBadLinesNamed) {
  std::vector<PoseSample> poses;
  std::string reason;
  EXPECT_TRUE(ParseTum("# t tx ty tz qx qy qz qw\n\n0 0 0 0 0 0 0 1\n", &poses, &reason));
  EXPECT_EQ(poses.size(), 1u);
  EXPECT_FALSE(ParseTum("0 0 0 0 0 0 0 1\n0 0 0\n", &poses, &reason));
  EXPECT_EQ(reason, "line 2: expected 8 numbers");
  EXPECT_FALSE(ParseTum("0 0 0 0 0 0 0 1 9\n", &poses, &reason));
  EXPECT_EQ(reason, "line 1: more than 8 fields");
}

}  // namespace
}  // namespace relplane::eval
