// The pipeline benchmark's report: the bus floor and ratios to it, the headline naming each
// failing check, the note on other work, progress lines and a histogram whose title and axes
// are whole.

#include "report.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace relplane::bench {
namespace {

// A 160x120 run at 30 Hz with every figure given.
BenchReport Report(double e2e_p50, double e2e_p99, double floor_cloud, double floor_pose,
                   double mapper_cpu, double mapper_alone, double other_cores) {
  ResolutionResult res;
  res.name = "160x120";
  RateResult r;
  r.rate_hz = 30.0;
  r.achieved_hz = 30.0;
  r.frames = 300;
  r.held = e2e_p99 <= 33.3;
  r.end_to_end.p50_ms = e2e_p50;
  r.end_to_end.p99_ms = e2e_p99;
  r.end_to_end.count = 300;
  r.mapper_cpu_ms = mapper_cpu;
  r.other_cores = other_cores;
  r.load_average = 3.5;
  RateResult fast = r;
  fast.rate_hz = 300.0;
  res.rates = {r, fast};
  res.floor.cloud_round_trip = Summarise({floor_cloud});
  res.floor.pose_round_trip = Summarise({floor_pose});
  res.mapper_compute = Summarise({mapper_alone});
  res.e2e_ms_at_30hz = std::vector<double>(300, e2e_p50);
  BenchReport report;
  report.scenario = "scenarios/office.yaml";
  report.resolutions.push_back(res);
  return report;
}

TEST(BusFloor, ThreeHopsAreACloudRoundTripAndHalfAPoseRoundTrip) {
  BusFloor floor;
  EXPECT_LT(floor.PipelineFloorMs(), 0.0);  // not measured
  floor.cloud_round_trip = Summarise({0.4, 0.5, 0.6});
  floor.pose_round_trip = Summarise({0.2});
  EXPECT_DOUBLE_EQ(floor.PipelineFloorMs(), 0.6);
  EXPECT_DOUBLE_EQ(RatioToFloor(1.8, 0.6), 3.0);
  EXPECT_LT(RatioToFloor(1.8, -1.0), 0.0);
  EXPECT_LT(RatioToFloor(0.0, 0.6), 0.0);
}

TEST(BusFloor, PingsCarryTheirSequenceNumberFirst) {
  const std::vector<uint8_t> ping = MakePing(123456789012, 230000);
  EXPECT_EQ(ping.size(), 230000u);
  EXPECT_EQ(PingSeq(ping.data(), ping.size()), 123456789012);
  EXPECT_EQ(PingSeq(ping.data(), kFloorReplyBytes), 123456789012);  // the reply's head
  EXPECT_EQ(MakePing(7, 2).size(), 8u);
  EXPECT_EQ(PingSeq(ping.data(), 4), -1);
}

TEST(Headline, NamesEachFailingCheck) {
  // p50 2.0 ms over a 0.5 ms floor (4x), mapper process 0.9 ms over 0.05 ms alone (18x).
  const Verdict failing = Judge(Report(2.0, 4.0, 0.4, 0.2, 0.9, 0.05, 0.0));
  EXPECT_FALSE(failing.pass);
  const std::string headline = Headline(failing);
  EXPECT_EQ(headline.rfind("FAIL: 2 of ", 0), 0u) << headline;
  EXPECT_NE(headline.find("p50 end to end <= 3x the bus floor at 30 Hz (2.00 ms = 4.0x 0.50 ms)"),
            std::string::npos)
      << headline;
  EXPECT_NE(headline.find("mapper process CPU per frame <= 2x its algorithm"), std::string::npos)
      << headline;
  EXPECT_EQ(headline.find("holds 30 it/s"), std::string::npos) << "a passing check is named";

  const Verdict passing = Judge(Report(1.0, 4.0, 0.4, 0.2, 0.06, 0.05, 0.0));
  EXPECT_TRUE(passing.pass) << Headline(passing);
  EXPECT_EQ(Headline(passing), "PASS: all " + std::to_string(passing.lines.size()) + " checks");
}

TEST(LoadNote, SaysWhenOtherWorkSharedTheMachine) {
  EXPECT_EQ(LoadNote(Report(1.0, 4.0, 0.4, 0.2, 0.06, 0.05, 0.02)), "");
  const std::string note = LoadNote(Report(1.0, 4.0, 0.4, 0.2, 0.06, 0.05, 1.25));
  EXPECT_NE(note.find("other processes used 1.25 cores"), std::string::npos) << note;
  EXPECT_NE(note.find("load average up to 3.50"), std::string::npos) << note;
  std::ostringstream table;
  const BenchReport loaded = Report(1.0, 4.0, 0.4, 0.2, 0.06, 0.05, 1.25);
  PrintTable(loaded, Judge(loaded), table);
  EXPECT_NE(table.str().find(note), std::string::npos);
}

TEST(ProgressLine, GivesTheRateLatencyRatioCpuAndLoad) {
  const BenchReport report = Report(1.5, 4.0, 0.4, 0.2, 0.06, 0.05, 0.5);
  const ResolutionResult& res = report.resolutions[0];
  const std::string line = ProgressLine(res.name, res.rates[0], res.floor);
  EXPECT_EQ(line.rfind("160x120 at 30 Hz: got 30.0 it/s, drops 0, e2e p50 1.50 p99 4.00 ms", 0),
            0u)
      << line;
  EXPECT_NE(line.find("(p50 3.0x the bus floor)"), std::string::npos) << line;
  EXPECT_NE(line.find("held; other processes 0.50 cores, load 3.50"), std::string::npos) << line;
}

// Characters of the widest line of text a 12 px sans-serif line of `width` pixels holds whole
// (a generous 7 px per character).
size_t FitsIn(int width_px) { return static_cast<size_t>(width_px / 7); }

TEST(HistogramSvg, TitleAndAxisLabelsFitTheFigure) {
  std::ostringstream svg;
  WriteHistogramSvg(Report(1.5, 4.0, 0.4, 0.2, 0.06, 0.05, 0.0), svg);
  const std::string text = svg.str();
  // The <svg ...> tag's width="N", then the text of each <text ...>LINE</text>.
  const size_t svg_tag = text.find("<svg");
  ASSERT_NE(svg_tag, std::string::npos);
  const size_t width_at = text.find(" width=\"", svg_tag);
  ASSERT_LT(width_at, text.find('>', svg_tag));
  const int width_px = std::stoi(text.substr(width_at + 8));
  bool title = false, x_axis = false, y_axis = false;
  for (size_t end = text.find("</text>"); end != std::string::npos;
       end = text.find("</text>", end + 1)) {
    const size_t start = text.rfind('>', end - 1) + 1;
    ASSERT_LT(start, end) << "empty or nested <text> at " << end;
    const std::string line = text.substr(start, end - start);
    ASSERT_EQ(line.find('<'), std::string::npos) << line;
    // Labels start at the 70 px left margin at most: each must end inside the figure.
    EXPECT_LE(line.size(), FitsIn(width_px - 70)) << "clipped: " << line;
    title = title || line.find("160x120 clouds at 30 Hz: end-to-end latency") != std::string::npos;
    x_axis = x_axis || line == "end-to-end latency, ms";
    y_axis = y_axis || line == "frames per bin";
  }
  EXPECT_TRUE(title);
  EXPECT_TRUE(x_axis);
  EXPECT_TRUE(y_axis);
}

}  // namespace
}  // namespace relplane::bench
