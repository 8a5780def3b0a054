// The accuracy targets on the three scenarios, with the simulator's own worlds and
// sensors (every 10th frame): noise-free <= 0.2 deg and <= 5 mm, sigma = 1 cm <= 1 deg and
// <= 2 cm, precision and recall >= 0.95.

#include "scenario_accuracy.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace relplane::segmenter::testing {
namespace {

const char* const kScenarios[] = {"straight_hallway", "hallway_loop", "office"};

void Check(double sigma, double max_angle_deg, double max_offset_m, double min_pr = 0.95) {
  for (const char* name : kScenarios) {
    SCOPED_TRACE(name);
    const std::string file = std::string(RELPLANE_SOURCE_DIR) + "/scenarios/" + name + ".yaml";
    const ScenarioAccuracy a = MeasureScenario(file, sigma, 10);
    std::printf("| %s | %.0f | %d | %.3f | %.3f | %.4f | %.2f |\n", name, sigma * 100, a.frames,
                a.Precision(), a.Recall(), a.median_angle_deg, a.median_offset_m * 1000);
    EXPECT_GT(a.true_planes, 0);
    EXPECT_GE(a.Precision(), min_pr);
    EXPECT_GE(a.Recall(), min_pr);
    EXPECT_LE(a.median_angle_deg, max_angle_deg);
    EXPECT_LE(a.median_offset_m, max_offset_m);
  }
}

TEST(ScenarioAccuracy, NoiseFree) { Check(0.0, 0.2, 0.005); }
TEST(ScenarioAccuracy, OneCentimetreNoise) { Check(0.01, 1.0, 0.02); }
// Beyond the targets (the defaults are meant for sigma up to 2 cm): a regression guard
// at today's level. The office falls short of 0.95 here (0.93 / 0.94): small door-frame
// rectangles drown in 2 cm noise.
TEST(ScenarioAccuracy, TwoCentimetreNoise) { Check(0.02, 1.0, 0.02, 0.9); }

// loop_other_sensor at 1 cm, noise seed 9, its first 111 frames, segmented in order (each
// frame's mixture starts from the last one's planes): around frame 100 a pilaster's 0.3 m side
// is 2 m ahead. EM fitted it as two planes 9 degrees apart, each with about half its points over
// the whole face, in 13 of those frames (options.merge.overlap_angle_deg).
TEST(ScenarioAccuracy, AFaceSeenAsTwoPlanesIsOne) {
  const std::string file = std::string(RELPLANE_SOURCE_DIR) + "/scenarios/loop_other_sensor.yaml";
  Options split;
  split.merge.overlap_angle_deg = 0.0f;  // pieces over each other merge only as near-identical
  const int before = FramesWithAWallTwice(file, 0.01, 9, 0, 110, split);
  std::printf("frames with a wall twice: %d of 111 without the overlap merge\n", before);
  ASSERT_GT(before, 5) << "the frames no longer show the split";
  EXPECT_EQ(FramesWithAWallTwice(file, 0.01, 9, 0, 110, Options{}), 0);
}

std::vector<WallSighting> Sightings(uint32_t seed, int64_t first, int64_t last,
                                    const Eigen::Vector2d& wall) {
  const std::string file = std::string(RELPLANE_SOURCE_DIR) + "/scenarios/loop_other_sensor.yaml";
  return WallSightings(file, 0.01, seed, first, last, Options{}, wall);
}

template <typename Pred>
long Count(const std::vector<WallSighting>& sightings, Pred pred) {
  return std::count_if(sightings.begin(), sightings.end(), pred);
}

// loop_other_sensor at 1 cm, noise seed 41, frames 40-80: a pilaster's 0.4 m front (y = 0.95,
// x from 6 to 6.4) 4-3 m ahead, at a grazing angle, its side square on. EM gave the front's piece
// a column or two of the side at the corner, and its fit leaned up to 7.7 degrees in a third of
// those frames without the line fit; the mapper made those sightings a second wall
// (DominantLineFit).
TEST(ScenarioAccuracy, AGrazingPilasterFrontDoesNotLeanTowardsItsSide) {
  const auto sightings = Sightings(41, 40, 80, {6.2, 0.95});
  auto leaning = [](const WallSighting& s) { return s.angle_deg > 2.5; };
  std::printf("front sightings over 2.5 degrees off: %ld of %zu\n", Count(sightings, leaning),
              sightings.size());
  ASSERT_GE(sightings.size(), 35u);
  EXPECT_EQ(Count(sightings, leaning), 0);
}

// The same on noise seed 47, frames 170-210, the pilaster at x = 11 closing in from 2.5 to
// 1.3 m: the front's mixture plane, 12 degrees off, took the side's samples up to 10 cm from the
// corner, and the side (x = 11, y from 0.95 to 1.25) was seen 0.18-0.2 m long; the mapper took
// its length from those sightings and put the front 10 cm off. With the front's plane set to its
// line and the frame assigned again, the side keeps its corner.
TEST(ScenarioAccuracy, APilasterSideKeepsTheCornerItSharesWithAGrazingFront) {
  const auto sightings = Sightings(47, 170, 210, {11.0, 1.1});
  auto short_side = [](const WallSighting& s) { return s.length_m < 0.25; };
  std::printf("side sightings under 0.25 m: %ld of %zu\n", Count(sightings, short_side),
              sightings.size());
  ASSERT_GE(sightings.size(), 35u);
  EXPECT_LE(Count(sightings, short_side), 2);
}

}  // namespace
}  // namespace relplane::segmenter::testing
