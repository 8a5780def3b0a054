#include "relplane/compare/report.hpp"

#include <algorithm>
#include <cstdio>

namespace relplane::compare {
namespace {

double MedianMs(std::vector<double> seconds) {
  if (seconds.empty()) return 0.0;
  auto middle = seconds.begin() + static_cast<std::ptrdiff_t>(seconds.size() / 2);
  std::nth_element(seconds.begin(), middle, seconds.end());
  return *middle * 1000.0;
}

}  // namespace

std::string Table(const std::vector<MethodStats>& stats) {
  std::string out =
      "| method | frames | time per frame (median, ms) | planes per frame | precision | recall "
      "| median angle | median offset | time / relplane |\n"
      "|---|---|---|---|---|---|---|---|---|\n";
  const double reference = stats.empty() ? 0.0 : MedianMs(stats.front().seconds);
  for (const MethodStats& s : stats) {
    const plane_truth::Accuracy a = s.tally.Summary();
    const double ms = MedianMs(s.seconds);
    char row[256];
    std::snprintf(
        row, sizeof(row), "| %s | %d | %.1f | %.1f | %.3f | %.3f | %.2f° | %.1f mm | %.1f× |\n",
        s.name.c_str(), a.frames, ms, a.frames ? static_cast<double>(s.planes) / a.frames : 0.0,
        a.Precision(), a.Recall(), a.median_angle_deg, a.median_offset_m * 1000.0,
        reference > 0.0 ? ms / reference : 0.0);
    out += row;
  }
  return out;
}

}  // namespace relplane::compare
