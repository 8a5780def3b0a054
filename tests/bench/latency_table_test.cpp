#include "latency_table.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "report.hpp"

namespace relplane::bench {
namespace {

// 100 frames at 30 Hz: segmenter 2 ms, mapper 1 ms, frame 7 never reaches POSE; frames
// slow_seq and slow_seq + 1 take 50 ms more.
LatencyTable HundredFrames(int64_t slow_seq = -1) {
  LatencyTable t;
  for (int64_t seq = 0; seq < 100; ++seq) {
    const int64_t pub = seq * 33333;
    t.Stamp(Stage::kPublished, seq, pub);
    t.Stamp(Stage::kPlanes, seq, pub + 2000);
    if (seq != 7) t.Stamp(Stage::kPose, seq, pub + 3000 + (slow_seq >= 0 && (seq == slow_seq || seq == slow_seq + 1) ? 50000 : 0));
  }
  return t;
}

TEST(LatencyTable, StagesMatchedBySeqAndDropsCounted) {
  const RateResult r = HundredFrames().Summarise(30.0, 3.3);
  EXPECT_EQ(r.frames, 100);
  EXPECT_EQ(r.dropped, 1);
  EXPECT_FALSE(r.held);  // a drop is never held
  EXPECT_DOUBLE_EQ(r.segmenter.p50_ms, 2.0);
  EXPECT_DOUBLE_EQ(r.mapper.p99_ms, 1.0);
  EXPECT_DOUBLE_EQ(r.end_to_end.max_ms, 3.0);
  EXPECT_NEAR(r.achieved_hz, 100 / 3.3, 1e-9);
}

TEST(LatencyTable, UnpacedIsJudgedAgainstTheRateItAchieved) {
  // 100 frames in 0.1 s (1 kHz) with 3 ms latency: no drops, but p99 exceeds the 1 ms period.
  LatencyTable t;
  for (int64_t seq = 0; seq < 100; ++seq) {
    t.Stamp(Stage::kPublished, seq, seq * 1000);
    t.Stamp(Stage::kPose, seq, seq * 1000 + 3000);
  }
  const RateResult r = t.Summarise(0.0, 0.1);
  EXPECT_EQ(r.dropped, 0);
  EXPECT_FALSE(r.held);
  EXPECT_TRUE(t.Summarise(0.0, 1.0).held);  // at 100 Hz the same latency fits the period
}

TEST(LatencyTable, RepeatedStampKeepsTheFirst) {
  LatencyTable t;
  t.Stamp(Stage::kPublished, 0, 0);
  t.Stamp(Stage::kPose, 0, 1000);
  t.Stamp(Stage::kPose, 0, 9000);
  EXPECT_EQ(t.EndToEndMs(), std::vector<double>{1.0});
}

TEST(Judge, FailsWhenP99ExceedsTheTarget) {
  BenchReport report;
  ResolutionResult small;
  small.name = "160x120";
  small.points_per_frame = 19200;
  LatencyTable ok;
  for (int64_t seq = 0; seq < 100; ++seq) {
    ok.Stamp(Stage::kPublished, seq, seq * 1000);
    ok.Stamp(Stage::kPose, seq, seq * 1000 + 900);
  }
  small.rates.push_back(ok.Summarise(30.0, 1.0));
  small.rates.push_back(ok.Summarise(480.0, 1.0));
  // p50 0.9 ms over a 0.6 ms floor; the mapper process at 1.25x its algorithm.
  small.floor.cloud_round_trip = Summarise({0.5});
  small.floor.pose_round_trip = Summarise({0.2});
  small.rates[0].mapper_cpu_ms = 0.1;
  small.mapper_compute = Summarise({0.08});
  report.resolutions.push_back(small);
  Verdict v = Judge(report);
  EXPECT_TRUE(v.pass) << Headline(v);
  EXPECT_EQ(HighestHeldRate(report.resolutions[0]), 480.0);

  // Two slow frames in a hundred at 30 Hz: p99 (nearest rank) is 53 ms.
  LatencyTable slow = HundredFrames(/*slow_seq=*/3);
  slow.Stamp(Stage::kPose, 7, 7 * 33333 + 3000);
  report.resolutions[0].rates[0] = slow.Summarise(30.0, 3.3);
  v = Judge(report);
  EXPECT_FALSE(v.pass);
  std::ostringstream json;
  WriteJson(report, v, json);
  EXPECT_NE(json.str().find("\"pass\": false"), std::string::npos);
}

}  // namespace
}  // namespace relplane::bench
