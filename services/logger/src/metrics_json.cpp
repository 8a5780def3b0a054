#include "relplane/eval/json_writer.hpp"
#include "relplane/eval/report_json.hpp"

namespace relplane::eval {
namespace {

void WriteLatency(JsonWriter& json, const std::string& key, const LatencySummary& s) {
  json.Key(key).BeginObject(true);
  json.Field("samples", s.samples).Field("p50_ms", s.p50_ms).Field("p99_ms", s.p99_ms);
  json.Field("max_ms", s.max_ms).EndObject();
}

void WriteSummary(JsonWriter& json, const std::string& key, const ErrorSummary& s) {
  json.Key(key).BeginObject(true).Field("mean", s.mean).Field("max", s.max).EndObject();
}

void WriteRun(JsonWriter& json, const RunCounts& r) {
  json.Key("run").BeginObject();
  json.Field("iterations", r.estimate_poses).Field("truth_poses", r.truth_poses);
  json.Field("map_updates", r.map_updates);
  json.Field("duration_s", r.duration_s).Field("wall_rate_hz", r.wall_rate_hz);
  json.Field("sim_rate_hz", r.sim_rate_hz);
  json.Key("pose_status").BeginObject(true);
  json.Field("tracking", r.tracking).Field("motion_model", r.motion_model);
  json.Field("initializing", r.initializing).Field("lost", r.lost).EndObject();
  json.EndObject();
}

void WriteTrajectory(JsonWriter& json, const TrajectoryMetrics& t) {
  json.Key("trajectory").BeginObject();
  json.Field("matched", t.matched).Field("path_length_m", t.path_length_m);
  json.Field("ate_rmse_m", t.ate_rmse_m).Field("ate_max_m", t.ate_max_m);
  json.Field("ate_final_m", t.ate_final_m).Field("ate_aligned_rmse_m", t.ate_aligned_rmse_m);
  json.Key("alignment").BeginObject(true);
  json.Field("x_m", t.alignment.x).Field("y_m", t.alignment.y);
  json.Field("yaw_deg", t.alignment.yaw * 180.0 / M_PI).EndObject();
  json.Field("yaw_rmse_deg", t.yaw_rmse_deg).Field("yaw_max_deg", t.yaw_max_deg);
  json.Key("rpe").BeginObject(true);
  json.Field("segment_m", t.rpe_segment_m).Field("segments", t.rpe_segments);
  json.Field("translation_m_per_m", t.rpe_translation_per_m);
  json.Field("rotation_deg_per_m", t.rpe_rotation_deg_per_m).EndObject();
  // Frames whose error lies within 3 sigma of the covariance POSE carried, overall and per status.
  const auto consistency = [&json](const std::string& key, const Consistency& c) {
    json.Key(key).BeginObject(true);
    json.Field("frames", c.frames).Field("position_within_3sigma", c.position_within_3sigma);
    json.Field("yaw_within_3sigma", c.yaw_within_3sigma).EndObject();
  };
  consistency("consistency", t.consistency);
  json.Key("consistency_by_status").BeginObject();
  const char* names[] = {"truth", "tracking", "motion_model", "initializing", "lost"};
  for (int s = 1; s < 5; ++s) consistency(names[s], t.consistency_by_status[s]);
  json.EndObject();
  json.EndObject();
}

void WriteMap(JsonWriter& json, const MapMetrics& m) {
  json.Key("map").BeginObject();
  json.Field("has_truth", m.has_truth).Field("true_walls", m.true_walls);
  json.Field("expected_walls", m.expected_walls).Field("mapped_planes", m.mapped_planes);
  json.Field("mapped_walls", m.mapped_walls);
  json.Field("mapped_without_extent", m.mapped_without_extent);
  json.Field("walls_mapped", m.walls_mapped).Field("partly_mapped", m.partly_mapped);
  json.Field("duplicates", m.duplicates);
  json.Field("other_faces", m.other_faces).Field("fragments", m.fragments);
  json.Field("spurious", m.spurious);
  json.Field("on_short_walls", m.on_short_walls).Field("missed", m.missed);
  WriteSummary(json, "normal_error_deg", m.normal_error_deg);
  WriteSummary(json, "offset_error_m", m.offset_error_m);
  WriteSummary(json, "endpoint_error_m", m.endpoint_error_m);
  json.Key("walls").BeginArray();
  for (const WallMatch& w : m.walls) {
    json.BeginObject(true);
    json.Field("true_id", w.true_id).Field("length_m", w.length_m).Field("expected", w.expected);
    json.Key("mapped_ids").BeginArray();
    for (const int64_t id : w.mapped_ids) json.Value(id);
    json.EndArray();
    json.Field("visible_length_m", w.visible_length_m).Field("mapped_length_m", w.mapped_length_m);
    json.Field("coverage", w.coverage).Field("mapped", w.mapped);
    json.Field("normal_error_deg", w.normal_error_deg).Field("offset_error_m", w.offset_error_m);
    json.Key("endpoint_error_m").Vector(w.endpoint_error_m, 2);
    json.Field("overlap_m", w.overlap_m);
    json.EndObject();
  }
  json.EndArray();
  json.Key("spurious_ids").BeginArray(true);
  for (const int64_t id : m.spurious_ids) json.Value(id);
  json.EndArray();
  json.EndObject();
}

void WriteTiming(JsonWriter& json, const TimingMetrics& t) {
  json.Key("timing").BeginObject();
  WriteLatency(json, "end_to_end", t.end_to_end);
  json.Key("stages").BeginObject();
  WriteLatency(json, "segmenter", t.segmenter);
  WriteLatency(json, "mapper", t.mapper);
  json.EndObject();
  json.Key("services").BeginObject();
  for (const auto& [name, s] : t.services) {
    json.Key(name).BeginObject(true);
    json.Field("reports", s.reports).Field("frames_processed", s.frames_processed);
    json.Field("frames_dropped", s.frames_dropped).Field("inputs_rejected", s.inputs_rejected);
    json.Field("p50_ms", s.p50_ms).Field("p99_ms", s.p99_ms).Field("max_ms", s.max_ms);
    json.EndObject();
  }
  json.EndObject();
  json.Field("frames_dropped_total", t.frames_dropped_total);
  json.EndObject();
}

}  // namespace

std::string MetricsToJson(const RunMetrics& metrics, const std::string& source) {
  JsonWriter json;
  json.BeginObject();
  json.Field("schema", "relplane-metrics/1").Field("source", source);
  WriteRun(json, metrics.run);
  WriteTrajectory(json, metrics.trajectory);
  WriteMap(json, metrics.map);
  WriteTiming(json, metrics.timing);
  bool all_pass = true;
  json.Key("expect").BeginArray();
  for (const ExpectationResult& e : metrics.expectations) {
    json.BeginObject(true);
    json.Field("key", e.key).Field("limit", e.limit).Field("value", e.value);
    json.Field("pass", e.pass).EndObject();
    all_pass = all_pass && e.pass;
  }
  json.EndArray();
  // null when the scenario expects nothing.
  json.Key("expect_pass");
  if (metrics.expectations.empty()) {
    json.Null();
  } else {
    json.Value(all_pass);
  }
  json.EndObject();
  return json.Str();
}

}  // namespace relplane::eval
