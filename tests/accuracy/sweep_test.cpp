#include "relplane/accuracy/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace relplane::accuracy {
namespace {

TEST(ParseSeeds, TakesRangesAndListsInTheOrderGiven) {
  EXPECT_EQ(ParseSeeds("1-6"), (std::vector<uint64_t>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(ParseSeeds("5,2"), (std::vector<uint64_t>{5, 2}));
  EXPECT_EQ(ParseSeeds("1-3,7"), (std::vector<uint64_t>{1, 2, 3, 7}));
  EXPECT_EQ(ParseSeeds("4"), (std::vector<uint64_t>{4}));
}

TEST(ParseSeeds, RefusesWhatIsNoPositiveSeed) {
  for (const char* bad : {"", "0", "a", "1,,2", "3-1", "-2", "1-", "2.5", "1-3,x", "+4"}) {
    EXPECT_THROW(ParseSeeds(bad), std::invalid_argument) << bad;
  }
}

// A run meeting every target, to be spoilt one way at a time.
RunResult Good() {
  RunResult r;
  r.frames = 100;
  r.trajectory.matched = 100;
  r.trajectory.ate_rmse_m = 0.02;
  r.map.walls_mapped = 5;
  r.map.normal_error_deg.max = 0.5;
  r.map.offset_error_m.max = 0.03;
  return r;
}

TEST(Misses, NoneForARunWithinEveryTarget) { EXPECT_TRUE(Misses(Good(), Targets{}).empty()); }

TEST(Misses, EachTargetMissedIsNamed) {
  RunResult r = Good();
  r.trajectory.ate_rmse_m = 0.051;
  EXPECT_EQ(Misses(r, {}), (std::vector<std::string>{"ATE 0.051 m"}));
  r = Good();
  r.map.duplicates = 2;
  EXPECT_EQ(Misses(r, {}), (std::vector<std::string>{"2 duplicates"}));
  r = Good();
  r.map.normal_error_deg.max = 1.2;
  EXPECT_EQ(Misses(r, {}), (std::vector<std::string>{"a wall 1.20° off"}));
  r = Good();
  r.map.offset_error_m.max = 0.087;
  EXPECT_EQ(Misses(r, {}), (std::vector<std::string>{"a wall 0.087 m off"}));
  r = Good();
  r.lost_frames = 3;
  EXPECT_EQ(Misses(r, {}), (std::vector<std::string>{"3 frames without a pose"}));
  r = Good();
  r.trajectory.matched = 99;  // a frame the conversions refused has no pose
  EXPECT_EQ(Misses(r, {}), (std::vector<std::string>{"1 frame without a pose"}));
}

TEST(Misses, NothingToScoreIsAMissNotAPass) {
  RunResult r = Good();
  r.trajectory.ate_rmse_m = std::nan("");
  r.map.walls_mapped = 0;
  r.map.normal_error_deg.max = std::nan("");
  r.map.offset_error_m.max = std::nan("");
  EXPECT_EQ(Misses(r, {}), (std::vector<std::string>{"ATE nan m", "no wall mapped"}));
}

TEST(Misses, TargetsAreTheCallersToSet) {
  RunResult r = Good();
  Targets loose;
  loose.duplicates = 1;
  r.map.duplicates = 1;
  EXPECT_TRUE(Misses(r, loose).empty());
  Targets tight;
  tight.ate_rmse_m = 0.01;
  EXPECT_EQ(Misses(Good(), tight).size(), 1u);
}

TEST(Summarise, CountsEachScenarioInTheOrderFirstSeen) {
  std::vector<SweepRun> runs(3);
  runs[0].scenario = "b";
  runs[0].seed = 1;
  runs[0].result.trajectory.ate_rmse_m = 0.01;
  runs[1].scenario = "a";
  runs[1].seed = 1;
  runs[1].result.trajectory.ate_rmse_m = 0.07;
  runs[1].misses = {"ATE 0.070 m"};
  runs[2].scenario = "b";
  runs[2].seed = 2;
  runs[2].result.trajectory.ate_rmse_m = 0.03;
  runs[2].misses = {"1 duplicate"};
  const std::vector<ScenarioSummary> s = Summarise(runs);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].scenario, "b");
  EXPECT_EQ(s[0].runs, 2);
  EXPECT_EQ(s[0].meeting, 1);
  EXPECT_NEAR(s[0].ate_sum_m, 0.04, 1e-12);
  EXPECT_NEAR(s[0].ate_worst_m, 0.03, 1e-12);
  EXPECT_EQ(s[0].failing_seeds, (std::vector<uint64_t>{2}));
  EXPECT_EQ(s[1].scenario, "a");
  EXPECT_EQ(s[1].meeting, 0);
}

TEST(FramesCsv, OneRowPerFrameWithItsStatusAndErrors) {
  RunResult r;
  FramePose tracked;
  tracked.seq = 0;
  tracked.status = 0;
  tracked.planes = 3;
  tracked.x = 1.0, tracked.y = 2.0, tracked.yaw = 0.1;
  tracked.true_x = 1.03, tracked.true_y = 2.04, tracked.true_yaw = 0.1 - M_PI / 180.0;
  FramePose refused;
  refused.seq = 1;
  r.poses = {tracked, refused};
  const std::string csv = FramesCsv(r);
  EXPECT_EQ(csv,
            "seq,status,planes,x,y,yaw,true_x,true_y,true_yaw,error_m,yaw_error_deg\n"
            "0,TRACKING,3,1.0000,2.0000,0.10000,1.0300,2.0400,0.08255,0.0500,1.000\n"
            "1,REFUSED,0,0.0000,0.0000,0.00000,0.0000,0.0000,0.00000,0.0000,0.000\n");
}

TEST(SweepJson, EachRunNamesItsScoredWallsWithTheirErrors) {
  SweepRun run;
  run.scenario = "office";
  run.seed = 3;
  run.result = Good();
  eval::WallMatch off;
  off.true_id = 7;
  off.expected = true;
  off.mapped_ids = {3, 9};
  off.normal_error_deg = 0.25;
  off.offset_error_m = 0.0625;
  eval::WallMatch unseen;  // no match: its errors stay NaN
  unseen.true_id = 8;
  run.result.map.walls = {off, unseen};
  run.result.wall_segments = {{{1.0, -1.0}, {4.5, -1.0}}, {}};
  const std::string json = SweepJson({run}, Targets{}, {});
  EXPECT_NE(json.find("\"walls\": ["), std::string::npos) << json;
  EXPECT_NE(json.find("{\"true_id\": 7, \"from\": [1, -1], \"to\": [4.5, -1], \"expected\": true, "
                      "\"matches\": 2, \"normal_error_deg\": 0.25, \"offset_error_m\": 0.0625}"),
            std::string::npos)
      << json;
  // No match: its errors are null, not a number that would pass for one.
  EXPECT_NE(json.find("\"true_id\": 8, \"from\": [0, 0], \"to\": [0, 0], \"expected\": false, "
                      "\"matches\": 0, \"normal_error_deg\": null, \"offset_error_m\": null}"),
            std::string::npos)
      << json;
}

TEST(SweepJson, EachRunGivesItsStraightLegsAndTheirAlongTrackError) {
  SweepRun run;
  run.scenario = "office";
  run.seed = 3;
  run.result = Good();
  // A 4 m leg along +x measured 0.1 m short.
  for (int i = 0; i <= 4; ++i) {
    FramePose& p = run.result.poses.emplace_back();
    p.seq = i;
    p.status = 0;
    p.true_x = i;
    p.x = 0.975 * i;
  }
  const std::string json = SweepJson({run}, Targets{}, {});
  EXPECT_NE(json.find("\"along_track_percent\": -2.5"), std::string::npos) << json;
  EXPECT_NE(
      json.find("{\"first_seq\": 0, \"last_seq\": 4, \"length_m\": 4, \"along_error_m\": -0.1"),
      std::string::npos)
      << json;
}

}  // namespace
}  // namespace relplane::accuracy
