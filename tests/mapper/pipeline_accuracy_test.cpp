// Issue 4 targets through the real EM segmenter, in one process: the simulator's
// frames are segmented and mapped as the services do (through their message conversions), and
// the map is scored by the evaluation's own metrics. The ideal-segmenter tests check the mapper
// alone; here a wall's last sample lands up to a ray spacing short of its end, as it does live.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "relplane/accuracy/scenario_run.hpp"

namespace relplane {
namespace {

using accuracy::RunResult;

// The scenario as its YAML has it; a sigma >= 0 and a seed > 0 replace the sensor's.
// `min_wall_length`: true walls shorter than this are not scored (the accuracy tables in
// docs/results.md leave out the doors' 0.30 m jambs, at the evaluation's limit, with 0.31).
// `world` > 0: random_indoor's generated world of that seed.
RunResult RunScenario(const std::string& name, double sigma = -1.0, uint64_t seed = 0,
                      double min_wall_length = 0.3, int world = 0) {
  accuracy::RunSpec spec;
  spec.min_wall_length_m = min_wall_length;
  if (world > 0) spec.overrides.push_back("sim.world.generators[0].seed=" + std::to_string(world));
  spec.file = std::string(RELPLANE_SOURCE_DIR) + "/scenarios/" + name + ".yaml";
  if (sigma >= 0.0) spec.overrides.push_back("sim.sensor.noise_sigma=" + std::to_string(sigma));
  if (seed > 0) spec.overrides.push_back("sim.sensor.seed=" + std::to_string(seed));
  const RunResult r = accuracy::RunScenario(spec);
  EXPECT_EQ(r.rejected_frames, 0);
  return r;
}

// The frames from `first` to `last` that have a pose.
std::vector<accuracy::FramePose> PosedFrames(const RunResult& r, int64_t first, int64_t last) {
  std::vector<accuracy::FramePose> frames;
  for (const accuracy::FramePose& f : r.poses) {
    if (f.seq >= first && f.seq <= last && f.status >= 0) frames.push_back(f);
  }
  return frames;
}

void ExpectExact(const RunResult& r, size_t min_ends) {
  EXPECT_LT(r.trajectory.ate_rmse_m, 0.01);
  EXPECT_EQ(r.map.duplicates, 0);
  EXPECT_LT(r.map.offset_error_m.max, 0.01);
  EXPECT_LT(r.map.normal_error_deg.max, 0.1);
  EXPECT_GE(r.reached_ends.size(), min_ends);  // not met by mapping nothing
  for (double error : r.reached_ends) EXPECT_LT(error, 0.01);
}

TEST(PipelineEnds, StraightHallwayNoiseFreeWallsEndAtTheirCorners) {
  // The side walls' far ends meet the end wall 6-8 m away, where rays are 6-8 cm apart.
  ExpectExact(RunScenario("straight_hallway"), 4);
}

TEST(PipelineEnds, OfficeNoiseFreeWallsEndAtTheirCorners) {
  ExpectExact(RunScenario("office"), 12);
}

// σ = 1 cm on the other sensor with a noise seed the scenario does not use: a partition's edge
// seen once 0.45 m into the door beside it (its pieces joined over the lintel) placed a door
// frame's group, and every room after it, 0.44 m along the partition (ATE 0.34 m).
// §II.D, generated world 1 (a training seed), sensor noise 1 cm. Turning in place at the start
// in a room's corner, the far corner 3.05 m away was the farthest edge seen for a while and piled
// up at one distance: learnt as the range, it cut the corner's ends (§II.C), no sighting from a
// fixed pose showed the first group's basis end any more, and its prior fell back to that wall's
// first sighting, whose end the view had cut 1.75 m from the start: the group and every pose
// after it went 0.74 m along the front wall. With nothing showing the end, the group stays where
// its last build put it.
TEST(PipelineAccuracy, GeneratedWorld1TheFirstGroupStaysWhenNoSightingShowsItsBasisEnd) {
  const RunResult r = RunScenario("random_indoor", 0.01);
  const std::vector<accuracy::FramePose> frames = PosedFrames(r, 0, 150);
  ASSERT_GT(frames.size(), 140u);
  for (const accuracy::FramePose& f : frames) {
    EXPECT_LT(std::hypot(f.x - f.true_x, f.y - f.true_y), 0.05) << "frame " << f.seq;
  }
}

// §II.D, generated world 78 (a development seed), 1 cm: a group's pairings through a far wall's
// ends, seen head on through a doorway as its ends crept with the sensor's approach, put two of
// four parallel walls 0.55 m one way and two the other, against the steady lines the four kept
// to each other; every pose after it went about a metre off (ATE 0.99 m). A point-placed
// member's line now comes from its parallel members' lines, the pairings standing along the walls.
TEST(PipelineAccuracy, GeneratedWorld78ParallelWallsKeepTheirLinesApart) {
  const RunResult r = RunScenario("random_indoor", 0.01, 0, 0.3, 78);
  EXPECT_LE(r.trajectory.ate_rmse_m, 0.05);
}

// §II.D, generated world 18 (a development seed), 1 cm: a wall's line from one parallel member
// (14 samples, 0.248 m) disagreed with the lines the others gave by 0.14 m; taken with them,
// it moved the wall and a group's pose by up to 0.25 m from frame to frame over 60 frames (ATE
// 0.06 m). A line disagreeing with the rest by more than parallel fits do is left out.
TEST(PipelineAccuracy, GeneratedWorld18ALineTheOtherLinesDisagreeWithIsLeftOut) {
  const RunResult r = RunScenario("random_indoor", 0.01, 0, 0.3, 18);
  EXPECT_LE(r.trajectory.ate_rmse_m, 0.04);
  for (const accuracy::FramePose& f : PosedFrames(r, 1700, 2300)) {
    EXPECT_LT(std::hypot(f.x - f.true_x, f.y - f.true_y), 0.15) << "frame " << f.seq;
  }
}

TEST(PipelineAccuracy, OfficeOtherSensorNoisySeed4) {
  const RunResult r = RunScenario("office_other_sensor", 0.01, 4);
  EXPECT_LE(r.trajectory.ate_rmse_m, 0.05);
  EXPECT_EQ(r.map.duplicates, 0);
  EXPECT_LT(r.map.offset_error_m.max, 0.05);
  EXPECT_LT(r.map.normal_error_deg.max, 1.0);
}

// σ = 1 cm, noise seed 11: at iteration 4 a wall end seen 9 cm short held the start back; every
// honest end after it lay more than a step ahead and was refused, so the position stood still
// while the sensor drove on, the first group was placed 0.3 m behind and 8 walls went unmatched
// (ATE 0.37 m). A position held still now takes an end up to a step further ahead for each
// iteration it was held (§II.E). The run still misses the targets (ATE 0.12 m: a segmenter fit
// running 0.26 m past a wall's end at iteration 20, see docs/decisions/mapper.md); this holds what
// was fixed.
TEST(PipelineAccuracy, OutAndBackNoisySeed11StartKeepsUpWithTheSensor) {
  const RunResult r = RunScenario("hallway_out_and_back", 0.01, 11, 0.31);
  // Frames 6-19 (the first metre once the bad end is past): 0.24 m behind on average before.
  const std::vector<accuracy::FramePose> frames = PosedFrames(r, 6, 19);
  ASSERT_EQ(frames.size(), 14u);
  double sum = 0.0;
  for (const accuracy::FramePose& f : frames) sum += std::hypot(f.x - f.true_x, f.y - f.true_y);
  EXPECT_LT(sum / static_cast<double>(frames.size()), 0.05);
  EXPECT_EQ(r.map.missed - r.map.partly_mapped, 0);  // no expected wall without a match
  EXPECT_LT(r.trajectory.ate_rmse_m, 0.2);
}

// σ = 1 cm, noise seed 41: walking through the door at y = 4.5 the far wall's two pieces beside
// the next door registered to new rltplanes, and only the door's 0.15 m jambs placed the pose
// (frames 474-481). Their headings wobbled 0.013-0.019 rad frame to frame; each wobble passed for
// a turn on the spot, the position stood still on three of the eight frames, and the next room
// and everything after it were mapped 5 cm back (ATE 0.049 m, a wall 6.1 cm off). Both are
// fixed: a turn must show over two iterations (mapper.cpp Predict), and a piece whose first
// choice another piece took keeps to the wall's older rltplane (registration.cpp).
TEST(PipelineAccuracy, OfficeOtherSensorNoisySeed41WalksThroughADoorOnItsJambs) {
  const RunResult r = RunScenario("office_other_sensor", 0.01, 41, 0.31);
  const std::vector<accuracy::FramePose> frames = PosedFrames(r, 474, 560);
  ASSERT_EQ(frames.size(), 87u);
  double worst = 0.0;
  for (const accuracy::FramePose& f : frames) worst = std::max(worst, std::abs(f.y - f.true_y));
  EXPECT_LT(worst, 0.02);  // 0.076 m before
  EXPECT_LE(r.trajectory.ate_rmse_m, 0.05);
  EXPECT_LT(r.map.offset_error_m.max, 0.05);
}

}  // namespace
}  // namespace relplane
