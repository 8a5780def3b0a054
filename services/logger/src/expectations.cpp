#include "relplane/eval/expectations.hpp"

#include <cmath>

namespace relplane::eval {

const std::vector<ExpectationKey>& ExpectationKeys() {
  static const std::vector<ExpectationKey> keys = {
      {"iterations_min", "POSE messages received", false},
      {"rate_min_hz", "POSE messages per second of host time", false},
      {"ate_rmse_max_m", "ATE RMSE in x-y, no alignment", true},
      // A run that cannot observe its position (featureless legs, no odometry) states it.
      {"ate_rmse_min_m", "ATE RMSE in x-y, no alignment, at least (an unobservable run)", false},
      {"ate_aligned_rmse_max_m", "ATE RMSE in x-y after SE(2) alignment", true},
      {"ate_final_max_m", "position error of the last matched pose", true},
      {"yaw_rmse_max_deg", "yaw error RMSE", true},
      {"rpe_max_m_per_m", "relative translation error per metre travelled (RMSE)", true},
      {"lost_max", "POSE messages with status LOST", true},
      {"walls_mapped_min", "true walls matched by a mapped plane", false},
      {"walls_mapped_fraction_min", "walls mapped / walls expected", false},
      {"duplicates_max", "extra mapped planes on an already matched wall", true},
      {"spurious_max", "mapped walls matching no true wall", true},
      {"missed_max", "expected true walls with no match", true},
      {"normal_error_max_deg", "largest normal angle error of a matched wall", true},
      {"offset_error_max_m", "largest offset error of a matched wall", true},
      {"endpoint_error_max_m", "largest end-point error of a matched wall", true},
      {"latency_p99_max_ms", "end-to-end latency p99 (SIM_TRUTH -> POSE)", true},
      {"dropped_max", "frames dropped, summed over services", true},
  };
  return keys;
}

double ExpectationValue(const std::string& key, const RunMetrics& m) {
  const auto count = [](int64_t v) { return static_cast<double>(v); };
  if (key == "iterations_min") return count(m.run.estimate_poses);
  if (key == "rate_min_hz") return m.run.wall_rate_hz;
  if (key == "ate_rmse_max_m" || key == "ate_rmse_min_m") return m.trajectory.ate_rmse_m;
  if (key == "ate_aligned_rmse_max_m") return m.trajectory.ate_aligned_rmse_m;
  if (key == "ate_final_max_m") return m.trajectory.ate_final_m;
  if (key == "yaw_rmse_max_deg") return m.trajectory.yaw_rmse_deg;
  if (key == "rpe_max_m_per_m") return m.trajectory.rpe_translation_per_m;
  if (key == "lost_max") return count(m.run.lost);
  // Map counts mean nothing without the true world.
  const bool map_count = key == "duplicates_max" || key == "spurious_max" || key == "missed_max" ||
                         key == "walls_mapped_min";
  if (map_count && !m.map.has_truth) return kNaN;
  if (key == "walls_mapped_min") return count(m.map.walls_mapped);
  if (key == "walls_mapped_fraction_min") {
    return m.map.expected_walls > 0 ? count(m.map.walls_mapped) / count(m.map.expected_walls)
                                    : kNaN;
  }
  if (key == "duplicates_max") return count(m.map.duplicates);
  if (key == "spurious_max") return count(m.map.spurious);
  if (key == "missed_max") return count(m.map.missed);
  if (key == "normal_error_max_deg") return m.map.normal_error_deg.max;
  if (key == "offset_error_max_m") return m.map.offset_error_m.max;
  if (key == "endpoint_error_max_m") return m.map.endpoint_error_m.max;
  if (key == "latency_p99_max_ms") return m.timing.end_to_end.p99_ms;
  if (key == "dropped_max") return count(m.timing.frames_dropped_total);
  return kNaN;
}

std::vector<ExpectationResult> CheckExpectations(const std::vector<Expectation>& expect,
                                                 const RunMetrics& metrics) {
  std::vector<ExpectationResult> results;
  for (const Expectation& e : expect) {
    ExpectationResult r;
    r.key = e.key;
    r.limit = e.limit;
    for (const ExpectationKey& k : ExpectationKeys()) {
      if (e.key == k.key) r.is_max = k.is_max;
    }
    r.value = ExpectationValue(e.key, metrics);
    r.pass = std::isfinite(r.value) && (r.is_max ? r.value <= e.limit : r.value >= e.limit);
    results.push_back(r);
  }
  return results;
}

}  // namespace relplane::eval
