#include "relplane/eval/summary.hpp"

#include <cmath>

#include "svg_util.hpp"

namespace relplane::eval {
namespace {

using svg::Format;

// "-" for a metric without data.
std::string Num(double v, const char* format = "%.3f") {
  return std::isfinite(v) ? Format(format, v) : std::string("-");
}

long long LL(int64_t v) { return static_cast<long long>(v); }

}  // namespace

std::string FormatSummary(const RunMetrics& m) {
  const RunCounts& r = m.run;
  const TrajectoryMetrics& t = m.trajectory;
  const MapMetrics& map = m.map;
  const TimingMetrics& timing = m.timing;
  std::string s = "relplane run summary\n";
  s += Format("  %-14s %lld poses (truth %lld), %s it/s host, %s it/s sim, %s s\n", "iterations",
              LL(r.estimate_poses), LL(r.truth_poses), Num(r.wall_rate_hz, "%.1f").c_str(),
              Num(r.sim_rate_hz, "%.1f").c_str(), Num(r.duration_s, "%.1f").c_str());
  s += Format("  %-14s tracking %lld, motion model %lld, initializing %lld, lost %lld\n",
              "pose status", LL(r.tracking), LL(r.motion_model), LL(r.initializing), LL(r.lost));
  s +=
      Format("  %-14s %s m (aligned %s m), max %s m, final %s m, yaw RMSE %s deg\n", "ATE RMSE",
             Num(t.ate_rmse_m).c_str(), Num(t.ate_aligned_rmse_m).c_str(), Num(t.ate_max_m).c_str(),
             Num(t.ate_final_m).c_str(), Num(t.yaw_rmse_deg, "%.2f").c_str());
  s += Format("  %-14s %s m/m, %s deg/m over %lld segments of %g m\n", "RPE",
              Num(t.rpe_translation_per_m, "%.4f").c_str(),
              Num(t.rpe_rotation_deg_per_m, "%.3f").c_str(), LL(t.rpe_segments), t.rpe_segment_m);
  if (map.has_truth) {
    s += Format(
        "  %-14s %lld planes, %lld walls; true walls mapped %lld/%lld expected (%lld true)"
        "; duplicates %lld, other faces %lld, fragments %lld, spurious %lld, missed %lld"
        " (%lld partly mapped)\n",
        "map", LL(map.mapped_planes), LL(map.mapped_walls), LL(map.walls_mapped),
        LL(map.expected_walls), LL(map.true_walls), LL(map.duplicates), LL(map.other_faces),
        LL(map.fragments), LL(map.spurious), LL(map.missed), LL(map.partly_mapped));
    s += Format("  %-14s normal max %s deg, offset max %s m, end point max %s m\n", "wall errors",
                Num(map.normal_error_deg.max, "%.2f").c_str(), Num(map.offset_error_m.max).c_str(),
                Num(map.endpoint_error_m.max).c_str());
  } else {
    s += Format("  %-14s %lld planes, %lld walls (no SIM_WORLD: not scored)\n", "map",
                LL(map.mapped_planes), LL(map.mapped_walls));
  }
  s += Format(
      "  %-14s end-to-end p50 %s ms, p99 %s ms, max %s ms; segmenter p99 %s ms; mapper "
      "p99 %s ms\n",
      "latency", Num(timing.end_to_end.p50_ms, "%.1f").c_str(),
      Num(timing.end_to_end.p99_ms, "%.1f").c_str(), Num(timing.end_to_end.max_ms, "%.1f").c_str(),
      Num(timing.segmenter.p99_ms, "%.1f").c_str(), Num(timing.mapper.p99_ms, "%.1f").c_str());
  if (!timing.services.empty()) {
    s += Format("  %-22s %8s %8s %8s %10s %8s %8s\n", "service", "p50 ms", "p99 ms", "max ms",
                "processed", "dropped", "rejected");
    for (const auto& [name, st] : timing.services) {
      s += Format("  %-22s %8s %8s %8s %10lld %8lld %8lld\n", name.c_str(),
                  Num(st.p50_ms, "%.2f").c_str(), Num(st.p99_ms, "%.2f").c_str(),
                  Num(st.max_ms, "%.2f").c_str(), LL(st.frames_processed), LL(st.frames_dropped),
                  LL(st.inputs_rejected));
    }
  }
  for (const ExpectationResult& e : m.expectations) {
    s += Format("  %-14s %-26s %10s %s %-8g %s\n", "expect", e.key.c_str(),
                Num(e.value, "%.4g").c_str(), e.is_max ? "<=" : ">=", e.limit,
                e.pass ? "PASS" : "FAIL");
  }
  return s;
}

}  // namespace relplane::eval
