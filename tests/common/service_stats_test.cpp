#include "relplane/common/service_stats.hpp"

#include <gtest/gtest.h>

namespace relplane {
namespace {

TEST(Percentile, NearestRank) {
  std::vector<double> v;
  for (int i = 1; i <= 100; ++i) v.push_back(i);
  EXPECT_EQ(Percentile(v, 0.5), 50);
  EXPECT_EQ(Percentile(v, 0.99), 99);
  EXPECT_EQ(Percentile(v, 1.0), 100);
  EXPECT_EQ(Percentile({}, 0.5), 0);
}

TEST(ServiceStats, CountsGapsRepeatsAndOrder) {
  ServiceStats stats("test", 10.0);
  EXPECT_TRUE(stats.AcceptSeq(0));
  EXPECT_TRUE(stats.AcceptSeq(1));
  EXPECT_TRUE(stats.AcceptSeq(4));   // 2 and 3 lost
  EXPECT_FALSE(stats.AcceptSeq(4));  // repeat
  EXPECT_FALSE(stats.AcceptSeq(2));  // late
  EXPECT_TRUE(stats.AcceptSeq(5));
  EXPECT_EQ(stats.Dropped(), 2);
  EXPECT_EQ(stats.Rejected(), 2);
}

TEST(ServiceStats, OneHugeSeqDoesNotPoisonTheStream) {
  ServiceStats stats("test", 10.0);
  for (int64_t k = 0; k < 10; ++k) EXPECT_TRUE(stats.AcceptSeq(k));
  EXPECT_FALSE(stats.AcceptSeq(INT64_MAX));  // hostile
  for (int64_t k = 10; k < 20; ++k) EXPECT_TRUE(stats.AcceptSeq(k)) << k;
  EXPECT_FALSE(stats.AcceptSeq(int64_t{1} << 40));  // hostile again, later
  EXPECT_TRUE(stats.AcceptSeq(21));                 // 20 lost
  EXPECT_EQ(stats.Rejected(), 2);
  EXPECT_EQ(stats.Dropped(), 1);
  EXPECT_EQ(stats.Resyncs(), 0);
}

TEST(ServiceStats, NegativeSeqIsRejected) {
  ServiceStats stats("test", 10.0);
  EXPECT_FALSE(stats.AcceptSeq(-1));
  EXPECT_TRUE(stats.AcceptSeq(0));
  EXPECT_FALSE(stats.AcceptSeq(INT64_MIN));
  EXPECT_TRUE(stats.AcceptSeq(1));
  EXPECT_EQ(stats.Rejected(), 2);
}

TEST(ServiceStats, GapWithinTheBoundIsDroppedNotSuspect) {
  ServiceStats stats("test", 10.0);
  EXPECT_TRUE(stats.AcceptSeq(5));
  EXPECT_TRUE(stats.AcceptSeq(5 + ServiceStats::kMaxSeqJump));
  EXPECT_EQ(stats.Dropped(), ServiceStats::kMaxSeqJump - 1);
  EXPECT_EQ(stats.Rejected(), 0);
}

TEST(ServiceStats, FarJumpConfirmedByTheNextFrameIsFollowed) {
  ServiceStats stats("test", 10.0);
  EXPECT_TRUE(stats.AcceptSeq(0));
  EXPECT_TRUE(stats.AcceptSeq(1));
  EXPECT_FALSE(stats.AcceptSeq(50000));  // suspect
  EXPECT_TRUE(stats.AcceptSeq(50001));   // confirmed: the source really jumped
  EXPECT_TRUE(stats.AcceptSeq(50002));
  EXPECT_FALSE(stats.AcceptSeq(2));  // the old stream is now old
  EXPECT_EQ(stats.Resyncs(), 1);
  EXPECT_EQ(stats.Dropped(), 0);  // a re-sync counts no drops: the gap is unknown
}

TEST(ServiceStats, SuspectNotFollowedIsForgotten) {
  ServiceStats stats("test", 10.0);
  EXPECT_TRUE(stats.AcceptSeq(0));
  EXPECT_FALSE(stats.AcceptSeq(50000));
  EXPECT_TRUE(stats.AcceptSeq(1));       // the real stream goes on
  EXPECT_FALSE(stats.AcceptSeq(50001));  // not confirming: the suspect was forgotten
  EXPECT_TRUE(stats.AcceptSeq(2));
  EXPECT_EQ(stats.Resyncs(), 0);
}

TEST(ServiceStats, RestartedSourceResyncsAfterAFewFrames) {
  ServiceStats stats("test", 10.0);
  for (int64_t k = 0; k < 100; ++k) EXPECT_TRUE(stats.AcceptSeq(k));
  // The simulator restarts at 0.
  for (int i = 0; i + 1 < ServiceStats::kResyncAfter; ++i) EXPECT_FALSE(stats.AcceptSeq(i));
  EXPECT_TRUE(stats.AcceptSeq(ServiceStats::kResyncAfter - 1));
  EXPECT_TRUE(stats.AcceptSeq(ServiceStats::kResyncAfter));
  EXPECT_EQ(stats.Resyncs(), 1);
  EXPECT_EQ(stats.Dropped(), 0);
}

TEST(ServiceStats, HugeFirstSeqIsOvercomeByTheRealStream) {
  ServiceStats stats("test", 10.0);
  EXPECT_TRUE(stats.AcceptSeq(INT64_MAX - 1));  // nothing to compare with yet
  EXPECT_FALSE(stats.AcceptSeq(0));
  EXPECT_FALSE(stats.AcceptSeq(1));
  EXPECT_TRUE(stats.AcceptSeq(2));
  EXPECT_TRUE(stats.AcceptSeq(3));
  EXPECT_EQ(stats.Dropped(), 0);
}

TEST(ServiceStats, RepeatsAndOutOfOrderDeliveryNeverResync) {
  ServiceStats stats("test", 10.0);
  for (int64_t k = 0; k <= 10; ++k) EXPECT_TRUE(stats.AcceptSeq(k));
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(stats.AcceptSeq(7));  // a repeated message
  EXPECT_FALSE(stats.AcceptSeq(9));
  EXPECT_FALSE(stats.AcceptSeq(8));  // not increasing: the run of older seqs starts again
  EXPECT_FALSE(stats.AcceptSeq(9));
  EXPECT_TRUE(stats.AcceptSeq(12));
  EXPECT_FALSE(stats.AcceptSeq(11));  // late
  EXPECT_TRUE(stats.AcceptSeq(13));
  EXPECT_EQ(stats.Resyncs(), 0);
  EXPECT_EQ(stats.Dropped(), 1);
}

TEST(ServiceStats, SnapshotTimingWindowResets) {
  ServiceStats stats("test", 10.0);
  for (int i = 1; i <= 10; ++i) stats.Processed(i);
  stats.Rejected("bad");
  StatusSnapshot s = stats.Snapshot();
  EXPECT_EQ(s.frames_processed, 10);
  EXPECT_EQ(s.inputs_rejected, 1);
  EXPECT_EQ(s.p50_ms, 5);
  EXPECT_EQ(s.max_ms, 10);
  EXPECT_EQ(s.detail, "bad");
  s = stats.Snapshot();
  EXPECT_EQ(s.frames_processed, 10);
  EXPECT_EQ(s.max_ms, 0);
}

}  // namespace
}  // namespace relplane
