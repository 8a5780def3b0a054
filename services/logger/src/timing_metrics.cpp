#include "relplane/eval/timing_metrics.hpp"

#include <algorithm>

#include "relplane/common/service_stats.hpp"

namespace relplane::eval {

LatencySummary Summarise(std::vector<double> samples_ms) {
  LatencySummary s;
  s.samples = static_cast<int64_t>(samples_ms.size());
  if (samples_ms.empty()) return s;
  s.p50_ms = Percentile(samples_ms, 0.5);
  s.p99_ms = Percentile(samples_ms, 0.99);
  s.max_ms = *std::max_element(samples_ms.begin(), samples_ms.end());
  return s;
}

void TimingRecorder::Arrived(Stage stage, int64_t seq, int64_t receive_us) {
  auto [it, inserted] = arrivals_.try_emplace(seq, std::array<int64_t, 3>{-1, -1, -1});
  if (it->second[stage] < 0) it->second[stage] = receive_us;
}

bool TimingRecorder::Status(const StatusSample& status) {
  const bool seen = reports_.count(status.service) > 0;
  Reports& r = reports_[status.service];
  const bool changed = !seen || status.frames_processed != r.last.frames_processed ||
                       status.frames_dropped != r.last.frames_dropped ||
                       status.inputs_rejected != r.last.inputs_rejected;
  // A report with nothing processed in its period carries no timing.
  if (status.frames_processed > r.last.frames_processed) {
    r.p50.push_back(status.p50_ms);
    r.p99 = std::max(r.p99, status.p99_ms);
    r.max = std::max(r.max, status.max_ms);
  }
  r.last = status;
  return changed;
}

TimingMetrics TimingRecorder::Compute() const {
  std::vector<double> end_to_end, segmenter, mapper;
  const auto span_ms = [](int64_t from, int64_t to) {
    return 1e-3 * static_cast<double>(to - from);
  };
  for (const auto& [seq, t] : arrivals_) {
    if (t[kCloud] >= 0 && t[kPose] >= 0) end_to_end.push_back(span_ms(t[kCloud], t[kPose]));
    if (t[kCloud] >= 0 && t[kPlanes] >= 0) segmenter.push_back(span_ms(t[kCloud], t[kPlanes]));
    if (t[kPlanes] >= 0 && t[kPose] >= 0) mapper.push_back(span_ms(t[kPlanes], t[kPose]));
  }
  TimingMetrics m;
  m.end_to_end = Summarise(end_to_end);
  m.segmenter = Summarise(segmenter);
  m.mapper = Summarise(mapper);
  for (const auto& [name, r] : reports_) {
    ServiceTiming& s = m.services[name];
    s.reports = static_cast<int64_t>(r.p50.size());
    s.frames_processed = r.last.frames_processed;
    s.frames_dropped = r.last.frames_dropped;
    s.inputs_rejected = r.last.inputs_rejected;
    if (r.last.frames_processed > 0) {
      s.p50_ms = Percentile(r.p50, 0.5);
      s.p99_ms = r.p99;
      s.max_ms = r.max;
    }
    m.frames_dropped_total += s.frames_dropped;
  }
  return m;
}

}  // namespace relplane::eval
