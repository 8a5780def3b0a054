#include "relplane/accuracy/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "relplane/accuracy/legs.hpp"
#include "relplane/eval/json_writer.hpp"

namespace relplane::accuracy {
namespace {

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

uint64_t ParseSeed(const std::string& text, const std::string& whole) {
  size_t used = 0;
  unsigned long long value = 0;
  try {
    if (text.empty() || text[0] == '-' || text[0] == '+') throw std::invalid_argument(text);
    value = std::stoull(text, &used);
  } catch (const std::logic_error&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || value == 0) {
    throw std::invalid_argument("seed list '" + whole + "': '" + text +
                                "' is not a positive whole number");
  }
  return value;
}

// NaN (nothing to score) counts as a miss.
bool Within(double value, double limit) { return std::isfinite(value) && value <= limit; }

}  // namespace

std::vector<uint64_t> ParseSeeds(const std::string& text) {
  std::vector<uint64_t> seeds;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string part = text.substr(start, comma - start);
    const size_t dash = part.find('-');
    if (dash == std::string::npos) {
      seeds.push_back(ParseSeed(part, text));
    } else {
      const uint64_t lo = ParseSeed(part.substr(0, dash), text);
      const uint64_t hi = ParseSeed(part.substr(dash + 1), text);
      if (hi < lo) throw std::invalid_argument("seed list '" + text + "': range '" + part +
                                               "' runs backwards");
      for (uint64_t s = lo; s <= hi; ++s) seeds.push_back(s);
    }
    start = comma + 1;
  }
  return seeds;
}

std::vector<std::string> Misses(const RunResult& r, const Targets& targets) {
  std::vector<std::string> misses;
  const eval::TrajectoryMetrics& t = r.trajectory;
  const eval::MapMetrics& m = r.map;
  if (!Within(t.ate_rmse_m, targets.ate_rmse_m)) {
    misses.push_back("ATE " + Format("%.3f m", t.ate_rmse_m));
  }
  if (m.duplicates > targets.duplicates) {
    misses.push_back(std::to_string(m.duplicates) + " duplicate" + (m.duplicates > 1 ? "s" : ""));
  }
  if (m.walls_mapped == 0) {
    misses.push_back("no wall mapped");
  } else {
    if (!Within(m.normal_error_deg.max, targets.normal_deg)) {
      misses.push_back("a wall " + Format("%.2f°", m.normal_error_deg.max) + " off");
    }
    if (!Within(m.offset_error_m.max, targets.offset_m)) {
      misses.push_back("a wall " + Format("%.3f m", m.offset_error_m.max) + " off");
    }
  }
  const int64_t without_pose = r.frames - t.matched + r.lost_frames;
  if (without_pose > 0) {
    misses.push_back(std::to_string(without_pose) + (without_pose > 1 ? " frames" : " frame") +
                     " without a pose");
  }
  return misses;
}

std::vector<ScenarioSummary> Summarise(const std::vector<SweepRun>& runs) {
  std::vector<ScenarioSummary> out;
  for (const SweepRun& run : runs) {
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const ScenarioSummary& s) { return s.scenario == run.scenario; });
    if (it == out.end()) {
      out.push_back({});
      it = out.end() - 1;
      it->scenario = run.scenario;
    }
    ++it->runs;
    const double ate = run.result.trajectory.ate_rmse_m;
    it->ate_sum_m += ate;
    it->ate_worst_m = std::max(it->ate_worst_m, ate);
    if (run.misses.empty()) {
      ++it->meeting;
    } else {
      it->failing_seeds.push_back(run.seed);
    }
  }
  return out;
}

std::vector<KindSummary> SummariseByKind(const std::vector<SweepRun>& runs,
                                         const Targets& targets) {
  std::vector<KindSummary> out;
  std::vector<std::vector<double>> ates;
  for (const SweepRun& run : runs) {
    const std::string kind = run.result.kind.Label();
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const KindSummary& s) { return s.kind == kind; });
    if (it == out.end()) {
      out.push_back({});
      ates.emplace_back();
      it = out.end() - 1;
      it->kind = kind;
    }
    const double ate = run.result.trajectory.ate_rmse_m;
    ++it->worlds;
    it->within_ate += ate <= targets.ate_rmse_m ? 1 : 0;
    it->with_duplicates += run.result.map.duplicates > 0 ? 1 : 0;
    it->ate_worst_m = std::max(it->ate_worst_m, ate);
    const double consistency = run.result.trajectory.consistency.position_within_3sigma;
    it->consistency += std::isfinite(consistency) ? consistency : 0.0;
    ates[static_cast<size_t>(it - out.begin())].push_back(ate);
  }
  for (size_t k = 0; k < out.size(); ++k) {
    std::vector<double>& a = ates[k];
    std::sort(a.begin(), a.end());
    out[k].ate_median_m = a.size() % 2 == 1 ? a[a.size() / 2]
                                            : 0.5 * (a[a.size() / 2 - 1] + a[a.size() / 2]);
    out[k].consistency /= static_cast<double>(out[k].worlds);
  }
  return out;
}

std::string KindTable(const std::vector<KindSummary>& kinds, const Targets& targets, double sigma) {
  // Markdown, so the table goes into docs/results as printed.
  std::string out = "| world kind | noise | worlds | ATE <= " + Format("%g m", targets.ate_rmse_m) +
                    " | median ATE | worst ATE | with duplicates | frames within 3 sigma |\n"
                    "|---|---|---|---|---|---|---|---|\n";
  const std::string noise = sigma >= 0.0 ? Format("%g m", sigma) : std::string("scenario's");
  for (const KindSummary& k : kinds) {
    char line[256];
    std::snprintf(line, sizeof line, "| %s | %s | %d | %d (%.0f %%) | %.3f m | %.3f m | %d | %.2f |\n",
                  k.kind.c_str(), noise.c_str(), k.worlds, k.within_ate,
                  100.0 * k.within_ate / std::max(k.worlds, 1), k.ate_median_m, k.ate_worst_m,
                  k.with_duplicates, k.consistency);
    out += line;
  }
  return out;
}

std::string RunLine(const SweepRun& run) {
  const RunResult& r = run.result;
  std::string line = run.scenario + " seed " +
                     (run.seed > 0 ? std::to_string(run.seed) : std::string("(own)")) + ": ATE " +
                     Format("%.3f m", r.trajectory.ate_rmse_m) + ", " +
                     std::to_string(r.map.duplicates) + " dup, worst wall " +
                     Format("%.2f°", r.map.normal_error_deg.max) + " / " +
                     Format("%.3f m", r.map.offset_error_m.max) + ", " +
                     std::to_string(r.map.missed) + " missed, " +
                     std::to_string(r.motion_model_frames) + " MOTION_MODEL frames";
  if (r.rejected_frames > 0) line += ", " + std::to_string(r.rejected_frames) + " rejected";
  if (r.rejected_odometry > 0) {
    line += ", " + std::to_string(r.rejected_odometry) + " odometry readings rejected";
  }
  if (run.misses.empty()) return line + ": meets the targets";
  line += ": misses (";
  for (size_t i = 0; i < run.misses.size(); ++i) line += (i ? "; " : "") + run.misses[i];
  return line + ")";
}

std::string FramesCsv(const RunResult& r) {
  static constexpr const char* kStatus[] = {"TRACKING", "MOTION_MODEL", "INITIALIZING", "LOST"};
  std::string out = "seq,status,planes,x,y,yaw,true_x,true_y,true_yaw,error_m,yaw_error_deg\n";
  char line[256];
  for (const FramePose& p : r.poses) {
    const char* status = p.status >= 0 && p.status < 4 ? kStatus[p.status] : "REFUSED";
    const double error = std::hypot(p.x - p.true_x, p.y - p.true_y);
    const double yaw_error = std::remainder(p.yaw - p.true_yaw, 2.0 * M_PI) * 180.0 / M_PI;
    std::snprintf(line, sizeof line, "%lld,%s,%d,%.4f,%.4f,%.5f,%.4f,%.4f,%.5f,%.4f,%.3f\n",
                  static_cast<long long>(p.seq), status, p.planes, p.x, p.y, p.yaw, p.true_x,
                  p.true_y, p.true_yaw, error, yaw_error);
    out += line;
  }
  return out;
}

std::string SweepJson(const std::vector<SweepRun>& runs, const Targets& targets,
                      const std::vector<std::string>& overrides) {
  eval::JsonWriter w;
  w.BeginObject();
  w.Key("targets").BeginObject(true);
  w.Field("ate_rmse_m", targets.ate_rmse_m).Field("duplicates", targets.duplicates);
  w.Field("normal_deg", targets.normal_deg).Field("offset_m", targets.offset_m);
  w.EndObject();
  w.Key("overrides").BeginArray(true);
  for (const std::string& o : overrides) w.Value(o);
  w.EndArray();
  w.Key("runs").BeginArray();
  for (const SweepRun& run : runs) {
    const RunResult& r = run.result;
    w.BeginObject();
    w.Field("scenario", run.scenario).Field("seed", static_cast<int64_t>(run.seed));
    w.Field("meets_targets", run.misses.empty());
    w.Key("misses").BeginArray(true);
    for (const std::string& miss : run.misses) w.Value(miss);
    w.EndArray();
    w.Field("frames", r.frames).Field("lost_frames", r.lost_frames);
    w.Field("motion_model_frames", r.motion_model_frames);
    w.Field("rejected_frames", r.rejected_frames);
    w.Field("rejected_odometry", r.rejected_odometry);
    w.Field("world_kind", r.kind.Label()).Field("unobservable_frames", r.kind.unobservable_frames);
    w.Field("longest_unobservable_s", r.kind.longest_stretch_s);
    w.Field("position_within_3sigma", r.trajectory.consistency.position_within_3sigma);
    w.Field("ate_rmse_m", r.trajectory.ate_rmse_m).Field("ate_max_m", r.trajectory.ate_max_m);
    w.Field("ate_aligned_rmse_m", r.trajectory.ate_aligned_rmse_m);
    w.Field("yaw_rmse_deg", r.trajectory.yaw_rmse_deg);
    w.Field("duplicates", r.map.duplicates).Field("other_faces", r.map.other_faces);
    w.Field("fragments", r.map.fragments);
    w.Field("spurious", r.map.spurious).Field("missed", r.map.missed);
    w.Field("walls_mapped", r.map.walls_mapped).Field("expected_walls", r.map.expected_walls);
    w.Field("normal_error_max_deg", r.map.normal_error_deg.max);
    w.Field("offset_error_max_m", r.map.offset_error_m.max);
    w.Field("endpoint_error_mean_m", r.map.endpoint_error_m.mean);
    // Each scored true wall with its best match's errors: which wall a run misses on.
    w.Key("walls").BeginArray();
    for (size_t k = 0; k < r.map.walls.size(); ++k) {
      const eval::WallMatch& wall = r.map.walls[k];
      const geometry::Segment2 at =
          k < r.wall_segments.size() ? r.wall_segments[k] : geometry::Segment2{};
      w.BeginObject(true);
      w.Field("true_id", wall.true_id);
      w.Key("from").BeginArray(true).Value(at.a.x()).Value(at.a.y()).EndArray();
      w.Key("to").BeginArray(true).Value(at.b.x()).Value(at.b.y()).EndArray();
      w.Field("expected", wall.expected);
      w.Field("matches", static_cast<int64_t>(wall.mapped_ids.size()));
      w.Field("normal_error_deg", wall.normal_error_deg);
      w.Field("offset_error_m", wall.offset_error_m);
      w.EndObject();
    }
    w.EndArray();
    // The straight legs' along-track errors: a distance driven measured short or long.
    const std::vector<Leg> legs = StraightLegs(r.poses);
    w.Field("along_track_percent", AlongTrackPercent(legs));
    w.Key("legs").BeginArray();
    for (const Leg& leg : legs) {
      w.BeginObject(true);
      w.Field("first_seq", leg.first_seq).Field("last_seq", leg.last_seq);
      w.Field("length_m", leg.length_m).Field("along_error_m", leg.along_error_m);
      w.EndObject();
    }
    w.EndArray();
    w.EndObject();
  }
  w.EndArray();
  w.Key("scenarios").BeginArray();
  for (const ScenarioSummary& s : Summarise(runs)) {
    w.BeginObject();
    w.Field("scenario", s.scenario).Field("runs", s.runs).Field("meeting_targets", s.meeting);
    w.Field("ate_sum_m", s.ate_sum_m).Field("ate_worst_m", s.ate_worst_m);
    w.Key("failing_seeds").BeginArray(true);
    for (uint64_t seed : s.failing_seeds) w.Value(static_cast<int64_t>(seed));
    w.EndArray();
    w.EndObject();
  }
  w.EndArray();
  w.EndObject();
  return w.Str() + "\n";
}

}  // namespace relplane::accuracy
