#include "bus_url.hpp"

#include <gtest/gtest.h>

#include <set>

namespace relplane::launch {
namespace {

TEST(ChoosePortTest, InRangeAndDeterministicForASeed) {
  const auto a = ChoosePort(12345, nullptr);
  ASSERT_TRUE(a.has_value());
  EXPECT_GE(*a, kFirstRunPort);
  EXPECT_LE(*a, kLastRunPort);
  EXPECT_EQ(ChoosePort(12345, nullptr), a);
}

TEST(ChoosePortTest, NearbySeedsSpreadOverTheRange) {
  std::set<int> ports;
  for (uint64_t seed = 1000; seed < 1100; ++seed) ports.insert(*ChoosePort(seed, nullptr));
  EXPECT_GE(ports.size(), 98u);  // consecutive pids must not land on neighbouring ports
}

TEST(ChoosePortTest, SkipsPortsInUse) {
  const int first = *ChoosePort(7, nullptr);
  const auto next = ChoosePort(7, [&](int port) { return port == first; });
  ASSERT_TRUE(next.has_value());
  EXPECT_NE(*next, first);
  EXPECT_FALSE(ChoosePort(7, [](int) { return true; }).has_value());
}

TEST(MakeUdpmUrlTest, IsolatedByPortWithTtlZero) {
  EXPECT_EQ(MakeUdpmUrl(40001, 0), "udpm://239.255.76.67:40001?ttl=0");
  EXPECT_EQ(MakeUdpmUrl(40001, 4194304), "udpm://239.255.76.67:40001?ttl=0&recv_buf_size=4194304");
}

TEST(PortOfUrlTest, ReadsUdpmPortsOnly) {
  EXPECT_EQ(PortOfUrl("udpm://239.255.76.67:40001?ttl=0"), 40001);
  EXPECT_EQ(PortOfUrl("udpm://239.255.76.67:7667"), 7667);
  EXPECT_EQ(PortOfUrl("udpm://239.255.76.67"), std::nullopt);
  EXPECT_EQ(PortOfUrl("memq://"), std::nullopt);
  EXPECT_EQ(PortOfUrl("udpm://239.255.76.67:99999"), std::nullopt);
}

TEST(BoundUdpPortsTest, ParsesProcNetUdp) {
  const std::string text =
      "   sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid  "
      "timeout inode ref pointer drops\n"
      "  123: 00000000:1DF3 00000000:0000 07 00000000:00000000 00:00000000 00000000     0    "
      "    0 1 2 0000000000000000 0\n"
      "  456: 0100007F:9C41 00000000:0000 07 00000000:00000000 00:00000000 00000000     0    "
      "    0 3 2 0000000000000000 0\n";
  EXPECT_EQ(BoundUdpPorts(text), (std::vector<int>{7667, 40001}));
  EXPECT_TRUE(BoundUdpPorts("").empty());
}

}  // namespace
}  // namespace relplane::launch
