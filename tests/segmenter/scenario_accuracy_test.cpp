// The accuracy targets on the three scenarios, with the simulator's own worlds and
// sensors (every 10th frame): noise-free <= 0.2 deg and <= 5 mm, sigma = 1 cm <= 1 deg and
// <= 2 cm, precision and recall >= 0.95.

#include "scenario_accuracy.hpp"

#include <gtest/gtest.h>

#include <cstdio>

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
// the whole face, in 13 of those frames (options.overlap_merge_angle_deg).
TEST(ScenarioAccuracy, AFaceSeenAsTwoPlanesIsOne) {
  const std::string file = std::string(RELPLANE_SOURCE_DIR) + "/scenarios/loop_other_sensor.yaml";
  Options split;
  split.overlap_merge_angle_deg = 0.0f;  // pieces over each other merge only as near-identical
  const int before = FramesWithAWallTwice(file, 0.01, 9, 0, 110, split);
  std::printf("frames with a wall twice: %d of 111 without the overlap merge\n", before);
  ASSERT_GT(before, 5) << "the frames no longer show the split";
  EXPECT_EQ(FramesWithAWallTwice(file, 0.01, 9, 0, 110, Options{}), 0);
}

}  // namespace
}  // namespace relplane::segmenter::testing
