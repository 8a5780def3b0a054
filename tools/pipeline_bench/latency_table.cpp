#include "latency_table.hpp"

#include <algorithm>
#include <utility>

#include "relplane/common/service_stats.hpp"

namespace relplane::bench {

void LatencyTable::Stamp(Stage stage, int64_t seq, int64_t micros) {
  stamps_[static_cast<int>(stage)].emplace(seq, micros);
}

LatencySummary Summarise(const std::vector<double>& ms) {
  LatencySummary s;
  s.count = static_cast<int>(ms.size());
  if (ms.empty()) return s;
  s.p50_ms = Percentile(ms, 0.50);
  s.p99_ms = Percentile(ms, 0.99);
  s.max_ms = *std::max_element(ms.begin(), ms.end());
  double sum = 0.0;
  for (double v : ms) sum += v;
  s.mean_ms = sum / static_cast<double>(ms.size());
  return s;
}

namespace {
// Milliseconds from stage `from` to stage `to` for every seq seen at both.
std::vector<double> Between(const std::map<int64_t, int64_t>& from,
                            const std::map<int64_t, int64_t>& to) {
  std::vector<double> ms;
  for (const auto& [seq, t_from] : from) {
    const auto it = to.find(seq);
    if (it != to.end()) ms.push_back((it->second - t_from) / 1000.0);
  }
  return ms;
}
}  // namespace

void LatencyTable::Forget() {
  for (auto& stage : stamps_) stage.clear();
}

std::vector<double> LatencyTable::EndToEndMs() const {
  return Between(stamps_[0], stamps_[2]);
}

RateResult LatencyTable::Summarise(double rate_hz, double publish_seconds) const {
  RateResult r;
  r.rate_hz = rate_hz;
  r.frames = static_cast<int>(stamps_[0].size());
  r.achieved_hz = publish_seconds > 0.0 ? r.frames / publish_seconds : 0.0;
  r.segmenter = bench::Summarise(Between(stamps_[0], stamps_[1]));
  r.mapper = bench::Summarise(Between(stamps_[1], stamps_[2]));
  r.end_to_end = bench::Summarise(EndToEndMs());
  std::vector<std::pair<double, int64_t>> by_latency;
  for (const auto& [seq, t_published] : stamps_[0]) {
    const auto it = stamps_[2].find(seq);
    if (it != stamps_[2].end()) by_latency.emplace_back(-(it->second - t_published), seq);
  }
  const size_t shown = std::min<size_t>(3, by_latency.size());
  std::partial_sort(by_latency.begin(), by_latency.begin() + shown, by_latency.end());
  for (size_t i = 0; i < shown; ++i) r.slowest_frames.push_back(by_latency[i].second);
  r.dropped = r.frames - r.end_to_end.count;
  // Unpaced, the frame period is the one actually achieved: queueing counts against it too.
  const double period_hz = rate_hz > 0.0 ? rate_hz : r.achieved_hz;
  const bool in_period = period_hz > 0.0 && r.end_to_end.p99_ms <= 1000.0 / period_hz;
  r.held = r.frames > 0 && r.dropped == 0 && in_period;
  return r;
}

}  // namespace relplane::bench
