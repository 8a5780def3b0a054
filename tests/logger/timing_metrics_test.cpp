// Latency by seq and the STATUS summary per service.
#include "relplane/eval/timing_metrics.hpp"

#include <gtest/gtest.h>

namespace relplane::eval {
namespace {

StatusSample Report(const std::string& service, int64_t processed, double p50, double p99,
                    double max, int64_t dropped) {
  StatusSample s;
  s.service = service;
  s.frames_processed = processed;
  s.p50_ms = p50;
  s.p99_ms = p99;
  s.max_ms = max;
  s.frames_dropped = dropped;
  return s;
}

TEST(TimingRecorder, LatencyPerStageAndEndToEndBySeq) {
  TimingRecorder t;
  for (int seq = 0; seq < 100; ++seq) {
    const int64_t cloud = 1000000 + seq * 33333;
    t.Arrived(TimingRecorder::kCloud, seq, cloud);
    t.Arrived(TimingRecorder::kPlanes, seq, cloud + 1000 * (1 + seq % 10));  // 1..10 ms
    if (seq != 50) t.Arrived(TimingRecorder::kPose, seq, cloud + 20000);     // seq 50 lost
  }
  t.Arrived(TimingRecorder::kPose, 3, 99999999);  // a repeat keeps the first arrival
  const TimingMetrics m = t.Compute();
  EXPECT_EQ(m.end_to_end.samples, 99);
  EXPECT_DOUBLE_EQ(m.end_to_end.p50_ms, 20.0);
  EXPECT_DOUBLE_EQ(m.end_to_end.max_ms, 20.0);
  EXPECT_EQ(m.segmenter.samples, 100);
  EXPECT_DOUBLE_EQ(m.segmenter.max_ms, 10.0);
  EXPECT_DOUBLE_EQ(m.segmenter.p99_ms, 10.0);
  EXPECT_DOUBLE_EQ(m.mapper.max_ms, 19.0);
  EXPECT_DOUBLE_EQ(m.mapper.p50_ms, 14.0);  // 10..19 ms, one 19 missing: rank 50 of 99
}

TEST(TimingRecorder, StatusReportsSummarisedPerService) {
  TimingRecorder t;
  EXPECT_TRUE(t.Status(Report("relplane-mapper", 0, 0, 0, 0, 0)));  // first: no timing yet
  EXPECT_TRUE(t.Status(Report("relplane-mapper", 30, 2.0, 5.0, 6.0, 0)));
  EXPECT_TRUE(t.Status(Report("relplane-mapper", 60, 3.0, 9.0, 12.0, 1)));
  EXPECT_TRUE(t.Status(Report("relplane-mapper", 90, 4.0, 7.0, 8.0, 3)));
  // An idle period repeats the counters: no timing, and no change worth a rewrite.
  EXPECT_FALSE(t.Status(Report("relplane-mapper", 90, 0.0, 0.0, 0.0, 3)));
  EXPECT_TRUE(t.Status(Report("relplane-sim", 90, 1.0, 1.0, 1.0, 2)));
  const TimingMetrics m = t.Compute();
  ASSERT_EQ(m.services.size(), 2u);
  const ServiceTiming& mapper = m.services.at("relplane-mapper");
  EXPECT_EQ(mapper.reports, 3);
  EXPECT_DOUBLE_EQ(mapper.p50_ms, 3.0);  // median of the per-second p50s
  EXPECT_DOUBLE_EQ(mapper.p99_ms, 9.0);  // largest per-second p99
  EXPECT_DOUBLE_EQ(mapper.max_ms, 12.0);
  EXPECT_EQ(mapper.frames_processed, 90);
  EXPECT_EQ(mapper.frames_dropped, 3);
  EXPECT_EQ(m.frames_dropped_total, 5);
}

}  // namespace
}  // namespace relplane::eval
