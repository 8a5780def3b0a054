#include "relplane/accuracy/scenario_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "relplane/common/options.hpp"

namespace relplane::accuracy {
namespace {

RunSpec Hallway(std::vector<std::string> overrides = {}) {
  RunSpec spec;
  spec.file = std::string(RELPLANE_SOURCE_DIR) + "/scenarios/straight_hallway.yaml";
  spec.overrides = std::move(overrides);
  return spec;
}

TEST(ScenarioRun, MapsTheStraightHallwayAndGivesEveryFrameAPose) {
  const RunResult r = RunScenario(Hallway());
  EXPECT_GT(r.frames, 100);
  EXPECT_EQ(r.rejected_frames, 0);
  EXPECT_EQ(r.lost_frames, 0);
  EXPECT_EQ(r.trajectory.matched, r.frames);
  EXPECT_LT(r.trajectory.ate_rmse_m, 0.01);
  EXPECT_GE(r.map.walls_mapped, 3);
  // Every scored wall is reported with where it stands, and every matched one is within 1 cm.
  ASSERT_EQ(r.wall_segments.size(), r.map.walls.size());
  int matched = 0;
  for (size_t k = 0; k < r.map.walls.size(); ++k) {
    const eval::WallMatch& wall = r.map.walls[k];
    EXPECT_GE(r.wall_segments[k].Length(), 0.3) << "wall " << wall.true_id;
    if (wall.mapped_ids.empty()) continue;
    ++matched;
    EXPECT_LT(wall.offset_error_m, 0.01) << "wall " << wall.true_id;
  }
  EXPECT_EQ(matched, r.map.walls_mapped);
}

// With plane_errors each frame's segmented walls come back against the true ones: the
// noise-free hallway's three walls in every frame, fitted to within a millimetre; without it, none.
TEST(ScenarioRun, KeepsEachFramesWallsAgainstTheTrueOnesWhenAsked) {
  EXPECT_TRUE(RunScenario(Hallway()).plane_errors.empty());
  RunSpec spec = Hallway();
  spec.plane_errors = true;
  const RunResult r = RunScenario(spec);
  std::set<int64_t> frames;
  for (const PlaneError& e : r.plane_errors) {
    frames.insert(e.seq);
    EXPECT_LT(std::abs(e.centroid_error_m), 0.001) << e.seq << " wall " << e.true_id;
    EXPECT_LT(std::abs(e.foot_error_m), 0.001) << e.seq << " wall " << e.true_id;
    EXPECT_GT(e.points, 0);
  }
  EXPECT_EQ(static_cast<int64_t>(frames.size()), r.frames);
  EXPECT_GE(r.plane_errors.size(), 3u * frames.size());
}

// The same spec gives the same numbers (no clock, fixed seeds); another noise seed gives others,
// so the seed override reaches the sensor.
TEST(ScenarioRun, IsRepeatableAndTheSeedOverrideReachesTheSensor) {
  const RunResult a = RunScenario(Hallway({"sim.sensor.noise_sigma=0.01", "sim.sensor.seed=2"}));
  const RunResult b = RunScenario(Hallway({"sim.sensor.noise_sigma=0.01", "sim.sensor.seed=2"}));
  const RunResult c = RunScenario(Hallway({"sim.sensor.noise_sigma=0.01", "sim.sensor.seed=3"}));
  EXPECT_EQ(a.trajectory.ate_rmse_m, b.trajectory.ate_rmse_m);
  EXPECT_EQ(a.map.offset_error_m.max, b.map.offset_error_m.max);
  EXPECT_NE(a.trajectory.ate_rmse_m, c.trajectory.ate_rmse_m);
  EXPECT_GT(a.trajectory.ate_rmse_m, 0.0);  // noise-free would be 0.000
}

TEST(ScenarioRun, BadInputIsAOneLineConfigError) {
  RunSpec missing = Hallway();
  missing.file = "/no/such/scenario.yaml";
  EXPECT_THROW(RunScenario(missing), config::ConfigError);
  EXPECT_THROW(CheckScenario(Hallway({"mapper.no_such_key=1"})), config::ConfigError);
  EXPECT_THROW(CheckScenario(Hallway({"sim.sensor.noise_sigma=[1, 2]"})), config::ConfigError);
  EXPECT_THROW(CheckScenario(Hallway({"no_equals_sign"})), config::ConfigError);
  EXPECT_NO_THROW(CheckScenario(Hallway({"sim.sensor.seed=9"})));
  try {
    CheckScenario(Hallway({"segmenter.no_such_key=1"}));
    FAIL() << "no error";
  } catch (const config::ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unknown key 'segmenter.no_such_key'"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace relplane::accuracy
