// MergeLogs: two recorders' logs become one, every event kept, in receive-time order.

#include "log_merge.hpp"

#include <gtest/gtest.h>
#include <lcm/eventlog.h>

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace relplane::launch {
namespace {

using Events = std::vector<std::pair<int64_t, std::string>>;  // timestamp, channel

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "/log_merge_test_" + name;
}

void WriteLog(const std::string& path, const Events& events) {
  lcm_eventlog_t* log = lcm_eventlog_create(path.c_str(), "w");
  ASSERT_NE(log, nullptr);
  for (const auto& [timestamp, channel] : events) {
    std::string data = channel + "@" + std::to_string(timestamp);
    lcm_eventlog_event_t event{};
    event.timestamp = timestamp;
    event.channellen = static_cast<int32_t>(channel.size());
    event.channel = const_cast<char*>(channel.c_str());
    event.datalen = static_cast<int32_t>(data.size());
    event.data = data.data();
    ASSERT_EQ(lcm_eventlog_write_event(log, &event), 0);
  }
  lcm_eventlog_destroy(log);
}

// The events of a log with their numbers, data checked against channel and time.
Events ReadLog(const std::string& path, std::vector<int64_t>* numbers) {
  Events events;
  lcm_eventlog_t* log = lcm_eventlog_create(path.c_str(), "r");
  if (!log) {
    ADD_FAILURE() << "cannot open " << path;
    return events;
  }
  while (lcm_eventlog_event_t* e = lcm_eventlog_read_next_event(log)) {
    events.emplace_back(e->timestamp, e->channel);
    numbers->push_back(e->eventnum);
    EXPECT_EQ(std::string(static_cast<char*>(e->data), e->datalen),
              std::string(e->channel) + "@" + std::to_string(e->timestamp));
    lcm_eventlog_free_event(e);
  }
  lcm_eventlog_destroy(log);
  return events;
}

TEST(MergeLogsTest, InterleavesByTimestampFirstLogFirstOnATieAndRenumbers) {
  const std::string a = TempPath("a"), b = TempPath("b"), out = TempPath("out");
  WriteLog(a, {{10, "POSE"}, {20, "SIM_TRUTH"}, {30, "POSE"}, {50, "MAP"}});
  WriteLog(b, {{5, "SENSOR_POINTS"}, {20, "SENSOR_POINTS"}, {40, "SENSOR_POINTS"}});
  std::string reason;
  ASSERT_TRUE(MergeLogs(a, b, out, &reason)) << reason;
  std::vector<int64_t> numbers;
  EXPECT_EQ(ReadLog(out, &numbers),
            (Events{{5, "SENSOR_POINTS"}, {10, "POSE"}, {20, "SIM_TRUTH"}, {20, "SENSOR_POINTS"},
                    {30, "POSE"}, {40, "SENSOR_POINTS"}, {50, "MAP"}}));
  EXPECT_EQ(numbers, (std::vector<int64_t>{0, 1, 2, 3, 4, 5, 6}));
  for (const auto& p : {a, b, out}) std::remove(p.c_str());
}

TEST(MergeLogsTest, AMissingOrEmptyLogCountsAsEmpty) {
  const std::string a = TempPath("only"), empty = TempPath("empty"), out = TempPath("out2");
  WriteLog(a, {{1, "POSE"}, {2, "POSE"}});
  std::fclose(std::fopen(empty.c_str(), "w"));
  std::string reason;
  std::vector<int64_t> numbers;
  ASSERT_TRUE(MergeLogs(a, TempPath("missing"), out, &reason)) << reason;
  EXPECT_EQ(ReadLog(out, &numbers).size(), 2u);
  ASSERT_TRUE(MergeLogs(empty, a, out, &reason)) << reason;
  EXPECT_EQ(ReadLog(out, &numbers).size(), 2u);
  for (const auto& p : {a, empty, out}) std::remove(p.c_str());
}

TEST(MergeLogsTest, AnUnwritableOutputIsAReason) {
  std::string reason;
  EXPECT_FALSE(MergeLogs(TempPath("x"), TempPath("y"), "/nonexistent-dir/out.lcmlog", &reason));
  EXPECT_NE(reason.find("/nonexistent-dir/out.lcmlog"), std::string::npos) << reason;
}

}  // namespace
}  // namespace relplane::launch
