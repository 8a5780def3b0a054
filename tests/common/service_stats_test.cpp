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
