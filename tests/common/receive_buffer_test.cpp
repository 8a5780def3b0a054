#include "relplane/common/receive_buffer.hpp"

#include <gtest/gtest.h>

namespace relplane::bus {
namespace {

TEST(ReceiveBufferTest, AUdpmUrlWithoutOneGetsTheBufferAsked) {
  EXPECT_EQ(WithReceiveBuffer("", 100), "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=100");
  EXPECT_EQ(WithReceiveBuffer("udpm://239.255.76.67:7667", 100),
            "udpm://239.255.76.67:7667?recv_buf_size=100");
  EXPECT_EQ(WithReceiveBuffer("udpm://239.255.76.67:40001?ttl=1", 100),
            "udpm://239.255.76.67:40001?ttl=1&recv_buf_size=100");
}

TEST(ReceiveBufferTest, AUrlThatSetsItOrIsNotUdpmIsKept) {
  EXPECT_EQ(WithReceiveBuffer("udpm://239.255.76.67:7667?recv_buf_size=5&ttl=0", 100),
            "udpm://239.255.76.67:7667?recv_buf_size=5&ttl=0");
  EXPECT_EQ(WithReceiveBuffer("memq://", 100), "memq://");
  EXPECT_EQ(WithReceiveBuffer("file:///tmp/x.lcmlog?mode=r", 100), "file:///tmp/x.lcmlog?mode=r");
}

TEST(ReceiveBufferTest, ReadsTheBufferAUrlAsksFor) {
  EXPECT_EQ(ReceiveBufferOfUrl("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"), 4194304);
  EXPECT_EQ(ReceiveBufferOfUrl("udpm://239.255.76.67:7667?recv_buf_size=7&ttl=0"), 7);
  EXPECT_EQ(ReceiveBufferOfUrl("udpm://239.255.76.67:7667?ttl=0"), 0);
  EXPECT_EQ(ReceiveBufferOfUrl("udpm://239.255.76.67:7667?recv_buf_size=lots"), 0);
  EXPECT_EQ(ReceiveBufferOfUrl(""), 0);
}

TEST(ReceiveBufferTest, NothingToDoWhenTheKernelCapIsHighEnough) {
  EXPECT_EQ(EnsureReceiveBufferMax(1), "");
}

}  // namespace
}  // namespace relplane::bus
