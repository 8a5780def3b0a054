#include "relplane/common/service_stats.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

namespace relplane {

double Percentile(std::vector<double> samples, double q) {
  if (samples.empty()) return 0.0;
  const size_t rank = static_cast<size_t>(std::ceil(q * samples.size()));
  const size_t index = std::min(samples.size() - 1, rank == 0 ? 0 : rank - 1);
  std::nth_element(samples.begin(), samples.begin() + index, samples.end());
  return samples[index];
}

ServiceStats::ServiceStats(std::string service, double budget_ms)
    : service_(std::move(service)), budget_ms_(budget_ms) {}

bool ServiceStats::AcceptSeq(int64_t seq) {
  if (seq < 0) {
    Rejected("seq " + std::to_string(seq) + " is negative");
    return false;
  }
  if (last_seq_ < 0) {  // the first frame sets the stream
    last_seq_ = seq;
    return true;
  }
  if (seq <= last_seq_) {
    // Older: late, repeated, or a source that started again. Only an increasing run of them
    // re-syncs, so neither a repeated message nor out-of-order delivery can.
    older_in_a_row_ = (older_in_a_row_ > 0 && seq > older_seq_) ? older_in_a_row_ + 1 : 1;
    older_seq_ = seq;
    suspect_seq_ = -1;
    if (older_in_a_row_ >= kResyncAfter) {
      spdlog::info("seq re-synced from {} back to {} ({} older seqs in a row: a restarted source)",
                   last_seq_, seq, older_in_a_row_);
      Resync(seq);
      return true;
    }
    Rejected("seq " + std::to_string(seq) + " is not after " + std::to_string(last_seq_));
    return false;
  }
  older_in_a_row_ = 0;
  if (seq - last_seq_ > kMaxSeqJump) {
    // Far ahead: held as a suspect until the next seq follows it.
    if (suspect_seq_ >= 0 && seq > suspect_seq_ && seq - suspect_seq_ <= kMaxSeqJump) {
      spdlog::info("seq re-synced from {} to {} (a jump confirmed by the next frame)", last_seq_,
                   seq);
      Resync(seq);
      return true;
    }
    suspect_seq_ = seq;
    Rejected("seq " + std::to_string(seq) + " is more than " + std::to_string(kMaxSeqJump) +
             " ahead of " + std::to_string(last_seq_));
    return false;
  }
  suspect_seq_ = -1;
  if (seq > last_seq_ + 1) dropped_ += seq - last_seq_ - 1;
  last_seq_ = seq;
  return true;
}

void ServiceStats::Resync(int64_t seq) {
  last_seq_ = seq;
  suspect_seq_ = -1;
  older_seq_ = -1;
  older_in_a_row_ = 0;
  ++resyncs_;
}

void ServiceStats::Processed(double elapsed_ms) {
  ++processed_;
  window_ms_.push_back(elapsed_ms);
  if (elapsed_ms > budget_ms_) {
    spdlog::debug("iteration took {:.2f} ms, over this service's budget of {:.1f} ms", elapsed_ms,
                  budget_ms_);
  }
}

void ServiceStats::Rejected(const std::string& reason) {
  ++rejected_;
  detail_ = reason;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_warning_ >= std::chrono::seconds(1)) {
    if (suppressed_warnings_ > 0) {
      spdlog::warn("rejected input: {} ({} more rejections since the last warning)", reason,
                   suppressed_warnings_);
    } else {
      spdlog::warn("rejected input: {}", reason);
    }
    last_warning_ = now;
    suppressed_warnings_ = 0;
  } else {
    ++suppressed_warnings_;
  }
}

StatusSnapshot ServiceStats::Snapshot() {
  StatusSnapshot s;
  s.frames_processed = processed_;
  s.frames_dropped = dropped_;
  s.inputs_rejected = rejected_;
  s.p50_ms = Percentile(window_ms_, 0.50);
  s.p99_ms = Percentile(window_ms_, 0.99);
  s.max_ms = window_ms_.empty() ? 0.0 : *std::max_element(window_ms_.begin(), window_ms_.end());
  s.last_seq = last_seq_;
  s.detail = detail_;
  const size_t over = std::count_if(window_ms_.begin(), window_ms_.end(),
                                    [this](double ms) { return ms > budget_ms_; });
  if (over > 0) {
    spdlog::warn(
        "{} of {} iterations in the last period exceeded the {:.1f} ms budget (max {:.2f} ms)",
        over, window_ms_.size(), budget_ms_, s.max_ms);
  }
  window_ms_.clear();
  return s;
}

}  // namespace relplane
