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

  // A seq further ahead of the last accepted one than this is held as a suspect: anything on
  // the bus can send anything, and one hostile huge seq must not make every real frame "old".
  static constexpr int64_t kMaxSeqJump = 1000;
  // This many consecutive older seqs, each after the previous one, re-sync the stream: a
  // restarted source (simulator, player) counts from 0 again.
  static constexpr int kResyncAfter = 3;

  // Checks the input's seq. Returns false (and counts a rejection) for a repeat or an older
  // seq, a negative seq, or a seq more than kMaxSeqJump ahead; a gap within the bound is
  // counted as dropped frames and accepted. Recovery, so that no single message poisons the
  // stream: a far-ahead seq is accepted when the next seq confirms it (follows it within the
  // bound); kResyncAfter older seqs in a row, increasing, are a restarted source and the last of
  // them is accepted. A re-sync counts no drops (the gap is unknown) and is logged.
  bool AcceptSeq(int64_t seq);
  void Processed(double elapsed_ms);
  // Counts frames this service dropped itself (e.g. the simulator's frame-loss option).
  void CountDropped(int64_t n) { dropped_ += n; }
  // Counts a rejected input and logs a warning at most once a second per service.
  void Rejected(const std::string& reason);
  void SetDetail(std::string detail) { detail_ = std::move(detail); }

  // Totals since start; timing over the samples since the previous snapshot.
  StatusSnapshot Snapshot();
  const std::string& Service() const { return service_; }
  int64_t Processed() const { return processed_; }
  int64_t Rejected() const { return rejected_; }
  int64_t Dropped() const { return dropped_; }
  int64_t Resyncs() const { return resyncs_; }

 private:
  void Resync(int64_t seq);

  std::string service_;
  double budget_ms_;
  int64_t processed_ = 0;
  int64_t dropped_ = 0;
  int64_t rejected_ = 0;
  int64_t last_seq_ = -1;
  int64_t suspect_seq_ = -1;  // a far-ahead seq waiting for confirmation, or -1
  int64_t older_seq_ = -1;    // the last of the current run of older seqs, or -1
  int older_in_a_row_ = 0;
  int64_t resyncs_ = 0;
  std::string detail_;
  std::vector<double> window_ms_;
  std::chrono::steady_clock::time_point last_warning_{};
  int64_t suppressed_warnings_ = 0;
};

}  // namespace relplane
