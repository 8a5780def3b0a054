// Reading a process's CPU time from /proc/PID/stat for the pipeline benchmark.
#include "process_cpu.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>

namespace relplane::bench {
namespace {

TEST(ProcessCpu, ParsesUserPlusSystemTicks) {
  // utime 250 and stime 50 ticks at 100 ticks/s: 3 s.
  const std::string stat =
      "4242 (relplane-segme) S 1 4242 4242 0 -1 4194304 97 0 0 0 250 50 0 0 20 0 3 0 2086300";
  const auto seconds = ParseProcStatCpuSeconds(stat, 100);
  ASSERT_TRUE(seconds.has_value());
  EXPECT_DOUBLE_EQ(*seconds, 3.0);
}

TEST(ProcessCpu, CountsFieldsFromTheLastParenthesis) {
  // A program name may hold spaces and ')' itself.
  const std::string stat = "7 (a) b (c) R 1 7 7 0 -1 0 0 0 0 0 10 20 0 0 20 0 1 0 5";
  EXPECT_DOUBLE_EQ(ParseProcStatCpuSeconds(stat, 10).value(), 3.0);
}

TEST(ProcessCpu, RejectsTextThatIsNotAStatLine) {
  EXPECT_FALSE(ParseProcStatCpuSeconds("", 100).has_value());
  EXPECT_FALSE(ParseProcStatCpuSeconds("12 (x) S 1 2 3", 100).has_value());
  EXPECT_FALSE(
      ParseProcStatCpuSeconds("no parenthesis at all 1 2 3 4 5 6 7 8 9 10 11 12", 100).has_value());
  EXPECT_FALSE(
      ParseProcStatCpuSeconds("7 (a) R 1 7 7 0 -1 0 0 0 0 0 10 20 0 0 20 0 1 0 5", 0).has_value());
}

TEST(ProcessCpu, OwnProcessUsesCpuWhileItWorks) {
  // Spins until the count moves by a tick; ten seconds bound it on a loaded machine.
  const double before = ProcessCpuSeconds(getpid()).value();
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  volatile double sink = 0.0;
  double after = before;
  while (after <= before && std::chrono::steady_clock::now() < until) {
    for (int i = 0; i < 100000; ++i) sink = sink + 1.0;
    after = ProcessCpuSeconds(getpid()).value();
  }
  EXPECT_GT(after, before);
  EXPECT_FALSE(ProcessCpuSeconds(-1).has_value());
}

TEST(MachineCpu, BusyIsEverythingButIdleAndIowait) {
  // user 100, nice 10, system 40, idle 900, iowait 50, irq 5, softirq 5, steal 40 ticks.
  const std::string stat = "cpu  100 10 40 900 50 5 5 40 0 0\ncpu0 50 5 20 450 25 2 3 20 0 0\n";
  EXPECT_DOUBLE_EQ(ParseMachineBusySeconds(stat, 100).value(), 2.0);
  EXPECT_FALSE(ParseMachineBusySeconds("intr 1 2 3\n", 100).has_value());
  EXPECT_FALSE(ParseMachineBusySeconds("cpu 1 2\n", 100).has_value());
  EXPECT_TRUE(MachineBusySeconds().has_value());
  EXPECT_GE(LoadAverage(), 0.0);
}

}  // namespace
}  // namespace relplane::bench
