#pragma once
// Latency bookkeeping of the pipeline benchmark: stamps per seq at each stage on one host
// monotonic clock, and the per-stage and end-to-end figures computed from them.
// Transport-free, so it is unit-tested without a bus.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace relplane::bench {

// Where a frame was seen, in order along the pipeline.
enum class Stage { kPublished = 0, kPlanes = 1, kPose = 2 };

struct LatencySummary {
  double p50_ms = 0.0;
  double p99_ms = 0.0;
  double max_ms = 0.0;
  double mean_ms = 0.0;
  int count = 0;
};

// The result of one run at one sensor rate.
struct RateResult {
  double rate_hz = 0.0;       // requested rate; 0 = unpaced
  double achieved_hz = 0.0;   // frames published / publishing time
  int frames = 0;             // frames published
  int dropped = 0;            // published frames with no POSE
  LatencySummary segmenter;   // PLANES receive - SENSOR_POINTS publish
  LatencySummary mapper;      // POSE receive - PLANES receive
  LatencySummary end_to_end;  // POSE receive - SENSOR_POINTS publish
  // The frames (their index in the run) with the longest end to end, slowest first: a tail made
  // by the first frames (buffers allocated, pages touched) tells apart from one in steady state.
  std::vector<int64_t> slowest_frames;
  // End to end of the warm-up frames sent before the run (Flags::warmup_frames), not in the
  // figures above.
  std::vector<double> warmup_ms;
  // CPU time (user + system, all threads) per frame published, ms; negative when unknown.
  // The sum over the processes bounds the rate the cores can hold whatever the scheduling.
  double segmenter_cpu_ms = -1.0;
  double mapper_cpu_ms = -1.0;
  double bench_cpu_ms = -1.0;  // this process: publishing and receiving every message
  // The rest of the machine during the run: CPU time of every other process per second of the
  // run, in cores (0: quiet), and the 1-minute load average at its end; negative when unknown.
  double other_cores = -1.0;
  double load_average = -1.0;
  // Held: nothing dropped and p99 end to end within one frame period (unpaced: the period of
  // the rate achieved).
  bool held = false;
};

class LatencyTable {
 public:
  // Records the first time `seq` reached `stage` (repeats are ignored).
  void Stamp(Stage stage, int64_t seq, int64_t micros);
  // Summarises the run; `rate_hz` 0 means unpaced, `publish_seconds` the publishing time.
  RateResult Summarise(double rate_hz, double publish_seconds) const;
  // End-to-end latencies in milliseconds, in seq order (for the histogram).
  std::vector<double> EndToEndMs() const;
  // Drops every stamp (after the warm-up frames).
  void Forget();

 private:
  std::map<int64_t, int64_t> stamps_[3];
};

LatencySummary Summarise(const std::vector<double>& ms);

}  // namespace relplane::bench
