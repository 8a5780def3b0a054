#pragma once
// The one recorder behind relplane-logger (live, from the bus) and relplane-eval (offline, from
// a bus.lcmlog): fed decoded messages with their receive time, it keeps the run and writes the
// run folder (trajectory.tum, truth.tum, map.json, metrics.json, map.svg, error.svg).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "relplane/eval/options.hpp"
#include "relplane/eval/run_metrics.hpp"
#include "relplane/eval/timing_metrics.hpp"
#include "relplane/eval/types.hpp"

namespace relplane::eval {

class RunRecorder {
 public:
  // `source` is written into metrics.json ("relplane-logger", "relplane-eval").
  RunRecorder(std::string out_dir, EvalOptions options, std::vector<Expectation> expect,
              std::string source);

  // `receive_us`: when the message arrived, one host clock for all channels (the logger's
  // monotonic clock, or the log's event timestamps).
  void OnPose(const PoseSample& pose, int64_t receive_us);
  void OnTruth(const PoseSample& pose, int64_t receive_us);
  void OnPlanes(int64_t seq, int64_t receive_us);
  void OnMap(MapSnapshot map, int64_t receive_us);
  void OnWorld(MapSnapshot world, int64_t receive_us);
  void OnStatus(const StatusSample& status, int64_t receive_us);

  // True when something arrived since the last Write().
  bool Changed() const { return changed_; }
  // For a writer working on a copy: the copy's Write() stands for this recorder's.
  void ClearChanged() { changed_ = false; }
  RunMetrics Metrics() const;
  // Rewrites every file of the run folder atomically. False with a one-line reason.
  bool Write(std::string* reason);
  // Metrics of the last Write() (computed there, so the summary matches the files).
  const RunMetrics& LastMetrics() const { return last_metrics_; }
  const std::string& OutDir() const { return out_dir_; }

 private:
  std::string out_dir_;
  EvalOptions options_;
  std::vector<Expectation> expect_;
  std::string source_;
  std::map<int64_t, PoseSample> estimate_;  // by seq: ordered, a repeat replaces
  std::map<int64_t, PoseSample> truth_;
  MapSnapshot map_;
  MapSnapshot world_;
  int64_t map_updates_ = 0;
  int64_t first_pose_us_ = -1;
  int64_t last_pose_us_ = -1;
  TimingRecorder timing_;
  RunMetrics last_metrics_;
  bool changed_ = true;  // the first Write() always writes, even an empty run
};

}  // namespace relplane::eval
