#pragma once
// The counters every service reports on STATUS (DESIGN.md): frames processed, dropped and
// rejected, and processing time percentiles. Transport-free so it is unit-tested alone.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace relplane {

struct StatusSnapshot {
  int64_t frames_processed = 0;
  int64_t frames_dropped = 0;
  int64_t inputs_rejected = 0;
  double p50_ms = 0.0;
  double p99_ms = 0.0;
  double max_ms = 0.0;
  int64_t last_seq = -1;
  std::string detail;
};

// Percentiles of a sample by nearest rank; q in [0, 1]. 0 for an empty sample.
double Percentile(std::vector<double> samples, double q);

class ServiceStats {
 public:
  // `budget_ms`: this service's share of the 33.3 ms iteration; slower iterations are warned.
  ServiceStats(std::string service, double budget_ms);

  // Checks the input's seq: a repeat or an older seq is rejected (returns false); a gap is
  // counted as dropped frames and accepted.
  bool AcceptSeq(int64_t seq);
  void Processed(double elapsed_ms);
  // Counts a rejected input and logs a warning at most once a second per service.
  void Rejected(const std::string& reason);
  void SetDetail(std::string detail) { detail_ = std::move(detail); }

  // Totals since start; timing over the samples since the previous snapshot.
  StatusSnapshot Snapshot();
  const std::string& Service() const { return service_; }
  int64_t Processed() const { return processed_; }
  int64_t Rejected() const { return rejected_; }
  int64_t Dropped() const { return dropped_; }

 private:
  std::string service_;
  double budget_ms_;
  int64_t processed_ = 0;
  int64_t dropped_ = 0;
  int64_t rejected_ = 0;
  int64_t last_seq_ = -1;
  std::string detail_;
  std::vector<double> window_ms_;
  std::chrono::steady_clock::time_point last_warning_{};
  int64_t suppressed_warnings_ = 0;
};

}  // namespace relplane
