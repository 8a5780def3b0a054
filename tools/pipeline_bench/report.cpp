#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace relplane::bench {
namespace {

const RateResult* FindRate(const ResolutionResult& r, double hz) {
  for (const auto& rate : r.rates) {
    if (rate.rate_hz == hz) return &rate;
  }
  return nullptr;
}

std::string Fixed(double v, int digits = 2) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

void JsonSummary(const char* name, const LatencySummary& s, std::ostream& out) {
  out << "\"" << name << "\": {\"p50_ms\": " << Fixed(s.p50_ms, 3)
      << ", \"p99_ms\": " << Fixed(s.p99_ms, 3) << ", \"max_ms\": " << Fixed(s.max_ms, 3)
      << ", \"mean_ms\": " << Fixed(s.mean_ms, 3)
      << ", \"count\": " << s.count << "}";
}

}  // namespace

double HighestHeldRate(const ResolutionResult& r) {
  double best = 0.0;
  for (const auto& rate : r.rates) {
    if (!rate.held) continue;
    best = std::max(best, rate.rate_hz > 0.0 ? rate.rate_hz : rate.achieved_hz);
  }
  return best;
}

Verdict Judge(const BenchReport& report) {
  Verdict v;
  auto check = [&v](bool ok, const std::string& what) {
    v.pass = v.pass && ok;
    v.lines.push_back(std::string(ok ? "PASS " : "FAIL ") + what);
  };
  for (const auto& res : report.resolutions) {
    const RateResult* at30 = FindRate(res, 30.0);
    if (at30 == nullptr) {
      check(false, res.name + ": no run at 30 Hz");
      continue;
    }
    if (res.name == "640x480") {
      check(at30->held, "640x480 holds 30 it/s: zero drops, p99 within 33.3 ms (drops " +
                            std::to_string(at30->dropped) + ", p99 " +
                            Fixed(at30->end_to_end.p99_ms) + " ms)");
      continue;
    }
    check(at30->held, res.name + " holds 30 it/s (drops " + std::to_string(at30->dropped) +
                          ", p99 " + Fixed(at30->end_to_end.p99_ms) + " ms)");
    if (res.name == "160x120") {
      check(at30->end_to_end.p99_ms <= 5.0,
            "160x120 p99 end to end <= 5 ms at 30 Hz (" + Fixed(at30->end_to_end.p99_ms) + " ms)");
      const double best = HighestHeldRate(res);
      check(best >= 300.0, "160x120 holds >= 300 it/s (" + Fixed(best, 0) + " it/s)");
      const double floor = res.floor.PipelineFloorMs();
      const double ratio = RatioToFloor(at30->end_to_end.p50_ms, floor);
      check(ratio > 0.0 && ratio <= 3.0,
            "160x120 p50 end to end <= 3x the bus floor at 30 Hz (" +
                Fixed(at30->end_to_end.p50_ms) + " ms = " + Fixed(ratio, 1) + "x " +
                Fixed(floor) + " ms)");
      const double cpu_ratio = RatioToFloor(at30->mapper_cpu_ms, res.mapper_compute.mean_ms);
      check(cpu_ratio > 0.0 && cpu_ratio <= 2.0,
            "160x120 mapper process CPU per frame <= 2x its algorithm alone at 30 Hz (" +
                Fixed(at30->mapper_cpu_ms, 3) + " ms = " + Fixed(cpu_ratio, 1) + "x " +
                Fixed(res.mapper_compute.mean_ms, 3) + " ms)");
    }
  }
  return v;
}

std::string Headline(const Verdict& verdict) {
  const size_t total = verdict.lines.size();
  std::vector<std::string> failed;
  for (const std::string& line : verdict.lines) {
    if (line.rfind("FAIL ", 0) == 0) failed.push_back(line.substr(5));
  }
  if (failed.empty()) return "PASS: all " + std::to_string(total) + " checks";
  std::string text = "FAIL: " + std::to_string(failed.size()) + " of " + std::to_string(total) +
                     " checks: ";
  for (size_t i = 0; i < failed.size(); ++i) text += (i ? "; " : "") + failed[i];
  return text;
}

MachineLoad LoadDuringRuns(const BenchReport& report) {
  MachineLoad load;
  double sum = 0.0;
  int count = 0;
  for (const auto& res : report.resolutions) {
    for (const auto& r : res.rates) {
      if (r.other_cores >= 0.0) sum += r.other_cores, ++count;
      load.load_average = std::max(load.load_average, r.load_average);
    }
  }
  if (count > 0) load.other_cores = sum / count;
  return load;
}

std::string LoadNote(const BenchReport& report) {
  const MachineLoad load = LoadDuringRuns(report);
  if (load.other_cores < 0.1) return "";
  return "note: other work was running: other processes used " + Fixed(load.other_cores, 2) +
         " cores on average during the runs (load average up to " +
         Fixed(load.load_average, 2) +
         "); latencies and rates are not a quiet machine's, CPU per frame and the ratios to "
         "the bus floor are less affected";
}

std::string ProgressLine(const std::string& resolution, const RateResult& r,
                         const BusFloor& floor) {
  std::ostringstream s;
  s << resolution << " at " << (r.rate_hz > 0 ? Fixed(r.rate_hz, 0) + " Hz" : std::string("max rate"))
    << ": got " << Fixed(r.achieved_hz, 1) << " it/s, drops " << r.dropped << ", e2e p50 "
    << Fixed(r.end_to_end.p50_ms) << " p99 " << Fixed(r.end_to_end.p99_ms) << " ms";
  const double ratio = RatioToFloor(r.end_to_end.p50_ms, floor.PipelineFloorMs());
  if (ratio > 0.0) s << " (p50 " << Fixed(ratio, 1) << "x the bus floor)";
  s << ", CPU/frame seg " << Fixed(r.segmenter_cpu_ms) << " map " << Fixed(r.mapper_cpu_ms, 3)
    << " ms, " << (r.held ? "held" : "NOT held");
  if (r.other_cores >= 0.0) {
    s << "; other processes " << Fixed(r.other_cores, 2) << " cores, load " << Fixed(r.load_average, 2);
  }
  return s.str();
}

void WriteJson(const BenchReport& report, const Verdict& verdict, std::ostream& out) {
  const MachineLoad load = LoadDuringRuns(report);
  out << "{\n  \"scenario\": \"" << report.scenario << "\",\n  \"machine\": \"" << report.machine
      << "\",\n  \"date\": \"" << report.date << "\",\n  \"buses\": \"" << report.buses
      << "\",\n  \"other_cores_mean\": " << Fixed(load.other_cores, 3)
      << ",\n  \"load_average_max\": " << Fixed(load.load_average, 2)
      << ",\n  \"pass\": " << (verdict.pass ? "true" : "false") << ",\n  \"checks\": [";
  for (size_t i = 0; i < verdict.lines.size(); ++i) {
    out << (i ? ", " : "") << "\"" << verdict.lines[i] << "\"";
  }
  out << "],\n  \"resolutions\": [\n";
  for (size_t i = 0; i < report.resolutions.size(); ++i) {
    const auto& res = report.resolutions[i];
    out << "    {\"name\": \"" << res.name << "\", \"points_per_frame\": " << res.points_per_frame
        << ", \"highest_rate_held_hz\": " << Fixed(HighestHeldRate(res), 1)
        << ", \"compute_ms\": {";
    JsonSummary("segmenter", res.segmenter_compute, out);
    out << ", ";
    JsonSummary("mapper", res.mapper_compute, out);
    out << "}, \"bus_floor\": {";
    JsonSummary("cloud_round_trip", res.floor.cloud_round_trip, out);
    out << ", ";
    JsonSummary("pose_round_trip", res.floor.pose_round_trip, out);
    out << ", \"pipeline_floor_ms\": " << Fixed(res.floor.PipelineFloorMs(), 3);
    out << "}, \"rates\": [\n";
    for (size_t j = 0; j < res.rates.size(); ++j) {
      const auto& r = res.rates[j];
      out << "      {\"rate_hz\": " << Fixed(r.rate_hz, 1) << ", \"achieved_hz\": "
          << Fixed(r.achieved_hz, 1) << ", \"frames\": " << r.frames
          << ", \"dropped\": " << r.dropped << ", \"held\": " << (r.held ? "true" : "false")
          << ", ";
      JsonSummary("segmenter", r.segmenter, out);
      out << ", ";
      JsonSummary("mapper", r.mapper, out);
      out << ", ";
      JsonSummary("end_to_end", r.end_to_end, out);
      out << ", \"cpu_ms_per_frame\": {\"segmenter\": " << Fixed(r.segmenter_cpu_ms, 3)
          << ", \"mapper\": " << Fixed(r.mapper_cpu_ms, 3)
          << ", \"bench\": " << Fixed(r.bench_cpu_ms, 3) << "}"
          << ", \"e2e_p50_to_floor\": "
          << Fixed(RatioToFloor(r.end_to_end.p50_ms, res.floor.PipelineFloorMs()), 2)
          << ", \"e2e_p99_to_floor\": "
          << Fixed(RatioToFloor(r.end_to_end.p99_ms, res.floor.PipelineFloorMs()), 2)
          << ", \"slowest_frames\": [";
      for (size_t i = 0; i < r.slowest_frames.size(); ++i) {
        out << (i ? ", " : "") << r.slowest_frames[i];
      }
      out << "], \"warmup_ms\": [";
      for (size_t i = 0; i < r.warmup_ms.size(); ++i) {
        out << (i ? ", " : "") << Fixed(r.warmup_ms[i], 3);
      }
      out << "]"
          << ", \"other_cores\": " << Fixed(r.other_cores, 3)
          << ", \"load_average\": " << Fixed(r.load_average, 2);
      out << "}" << (j + 1 < res.rates.size() ? "," : "") << "\n";
    }
    out << "    ]}" << (i + 1 < report.resolutions.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
}

void WriteHistogramSvg(const BenchReport& report, std::ostream& out) {
  // One panel per resolution: end-to-end latency at 30 Hz, 60 bins, with the 5 ms target, the
  // 33.3 ms budget and the bus floor marked when they fall in range. The margins hold the title
  // (two lines), the axis labels and the tick labels whole.
  const int panel_w = 560, panel_h = 200, left = 70, right = 30, top_margin = 48, bottom = 52;
  const int width = left + panel_w + right;
  const int height = static_cast<int>(report.resolutions.size()) * (top_margin + panel_h + bottom);
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  int top = 0;
  for (const auto& res : report.resolutions) {
    const auto& ms = res.e2e_ms_at_30hz;
    const double max_ms = ms.empty() ? 1.0 : *std::max_element(ms.begin(), ms.end());
    const double span = std::max(1.0, std::ceil(max_ms * 1.1));
    const int bins = 60;
    std::vector<int> counts(bins, 0);
    for (double v : ms) counts[std::min(bins - 1, static_cast<int>(v / span * bins))]++;
    const int peak = std::max(1, *std::max_element(counts.begin(), counts.end()));
    const int x0 = left, y_top = top + top_margin, y0 = y_top + panel_h;
    out << "<text x=\"" << x0 << "\" y=\"" << top + 18 << "\" font-weight=\"bold\">" << res.name
        << " clouds at 30 Hz: end-to-end latency, " << ms.size() << " frames</text>\n"
        << "<text x=\"" << x0 << "\" y=\"" << top + 34
        << "\" font-size=\"11\">from SENSOR_POINTS published to POSE received; bus floor "
        << Fixed(res.floor.PipelineFloorMs()) << " ms</text>\n";
    for (int b = 0; b < bins; ++b) {
      const double h = (panel_h - 10.0) * counts[b] / peak;
      out << "<rect x=\"" << x0 + b * panel_w / bins << "\" y=\"" << Fixed(y0 - h, 1)
          << "\" width=\"" << panel_w / bins - 1 << "\" height=\"" << Fixed(h, 1)
          << "\" fill=\"steelblue\"/>\n";
    }
    out << "<line x1=\"" << x0 << "\" y1=\"" << y0 << "\" x2=\"" << x0 + panel_w << "\" y2=\""
        << y0 << "\" stroke=\"black\"/>\n"
        << "<line x1=\"" << x0 << "\" y1=\"" << y_top << "\" x2=\"" << x0 << "\" y2=\"" << y0
        << "\" stroke=\"black\"/>\n";
    for (int t = 0; t <= 4; ++t) {
      const double v = span * t / 4;
      out << "<text x=\"" << x0 + t * panel_w / 4 << "\" y=\"" << y0 + 16
          << "\" text-anchor=\"" << (t == 4 ? "end" : t == 0 ? "start" : "middle") << "\">"
          << Fixed(v, 1) << "</text>\n";
    }
    out << "<text x=\"" << x0 + panel_w / 2 << "\" y=\"" << y0 + 36
        << "\" text-anchor=\"middle\">end-to-end latency, ms</text>\n";
    for (const auto& [count, y] : {std::pair<int, int>{peak, y0 - (panel_h - 10)}, {0, y0}}) {
      out << "<text x=\"" << x0 - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">" << count
          << "</text>\n";
    }
    out << "<text transform=\"translate(" << x0 - 40 << "," << y_top + panel_h / 2
        << ") rotate(-90)\" text-anchor=\"middle\">frames per bin</text>\n";
    const std::pair<double, const char*> marks[] = {
        {res.floor.PipelineFloorMs(), "bus floor"}, {5.0, "5 ms target"}, {1000.0 / 30.0, "33.3 ms budget"}};
    int label_row = 0;
    for (const auto& [mark, label] : marks) {
      if (mark <= 0.0 || mark > span) continue;
      const double x = x0 + mark / span * panel_w;
      const bool flip = x > x0 + panel_w - 100;  // keep the label inside the panel
      out << "<line x1=\"" << Fixed(x, 1) << "\" y1=\"" << y_top << "\" x2=\"" << Fixed(x, 1)
          << "\" y2=\"" << y0 << "\" stroke=\"" << (mark == marks[0].first ? "gray" : "red")
          << "\" stroke-dasharray=\"4,3\"/>\n"
          << "<text x=\"" << Fixed(flip ? x - 3 : x + 3, 1) << "\" y=\"" << y_top + 12 + 14 * label_row++
          << "\" fill=\"" << (mark == marks[0].first ? "gray" : "red") << "\" text-anchor=\""
          << (flip ? "end" : "start") << "\">" << label << "</text>\n";
    }
    top += top_margin + panel_h + bottom;
  }
  out << "</svg>\n";
}

void PrintTable(const BenchReport& report, const Verdict& verdict, std::ostream& out) {
  out << "relplane pipeline benchmark: " << report.scenario << " on " << report.machine << ", "
      << report.date << ", " << report.buses << "\n";
  out << std::left << std::setw(9) << "cloud" << std::right << std::setw(8) << "rate"
      << std::setw(9) << "got" << std::setw(7) << "drops" << std::setw(10) << "seg p50"
      << std::setw(10) << "seg p99" << std::setw(10) << "map p50" << std::setw(10) << "map p99"
      << std::setw(10) << "e2e p50" << std::setw(10) << "e2e p99" << std::setw(10) << "e2e max"
      << std::setw(9) << "seg cpu" << std::setw(9) << "map cpu" << "  held\n";
  for (const auto& res : report.resolutions) {
    for (const auto& r : res.rates) {
      out << std::left << std::setw(9) << res.name << std::right << std::setw(8)
          << (r.rate_hz > 0 ? Fixed(r.rate_hz, 0) : std::string("max")) << std::setw(9)
          << Fixed(r.achieved_hz, 1) << std::setw(7) << r.dropped << std::setw(10)
          << Fixed(r.segmenter.p50_ms) << std::setw(10) << Fixed(r.segmenter.p99_ms)
          << std::setw(10) << Fixed(r.mapper.p50_ms) << std::setw(10) << Fixed(r.mapper.p99_ms)
          << std::setw(10) << Fixed(r.end_to_end.p50_ms) << std::setw(10)
          << Fixed(r.end_to_end.p99_ms) << std::setw(10) << Fixed(r.end_to_end.max_ms)
          << std::setw(9) << Fixed(r.segmenter_cpu_ms) << std::setw(9) << Fixed(r.mapper_cpu_ms)
          << "  " << (r.held ? "yes" : "no") << "\n";
    }
    out << "  " << res.name << ": highest rate held " << Fixed(HighestHeldRate(res), 0)
        << " it/s\n";
    const double floor = res.floor.PipelineFloorMs();
    out << "  " << res.name << ": bus floor " << Fixed(floor) << " ms (round trips p50: cloud "
        << Fixed(res.floor.cloud_round_trip.p50_ms) << ", pose "
        << Fixed(res.floor.pose_round_trip.p50_ms) << " ms); e2e as a ratio to it, p50/p99:";
    for (const auto& r : res.rates) {
      out << " " << (r.rate_hz > 0 ? Fixed(r.rate_hz, 0) : std::string("max")) << " Hz "
          << Fixed(RatioToFloor(r.end_to_end.p50_ms, floor), 1) << "/"
          << Fixed(RatioToFloor(r.end_to_end.p99_ms, floor), 1);
    }
    out << "\n";
    out << "  " << res.name << ": compute alone (one thread, CPU time) segmenter p50 "
        << Fixed(res.segmenter_compute.p50_ms) << " p99 " << Fixed(res.segmenter_compute.p99_ms)
        << " max " << Fixed(res.segmenter_compute.max_ms) << ", mapper p50 "
        << Fixed(res.mapper_compute.p50_ms) << " p99 " << Fixed(res.mapper_compute.p99_ms)
        << " max " << Fixed(res.mapper_compute.max_ms) << " ms\n";
    if (const RateResult* at30 = FindRate(res, 30.0)) {
      out << "  " << res.name << ": process CPU per frame at 30 Hz over the algorithm alone (mean): "
          << "segmenter " << Fixed(RatioToFloor(at30->segmenter_cpu_ms, res.segmenter_compute.mean_ms), 1)
          << "x, mapper " << Fixed(RatioToFloor(at30->mapper_cpu_ms, res.mapper_compute.mean_ms), 1)
          << "x\n";
    }
    if (!res.rates.empty() && !res.rates.front().warmup_ms.empty()) {
      out << "  " << res.name << ": each run after " << res.rates.front().warmup_ms.size()
          << " warm-up frames, not timed (at " << Fixed(res.rates.front().rate_hz, 0)
          << " Hz they took";
      for (double ms : res.rates.front().warmup_ms) out << " " << Fixed(ms) << " ms";
      out << " end to end)\n";
    }
  }
  out << "(latencies in ms; 'held' = no drops and p99 end to end within one frame period;\n"
         " cpu = CPU ms per frame of the service process, all threads)\n";
  for (const auto& line : verdict.lines) out << line << "\n";
  if (const std::string note = LoadNote(report); !note.empty()) out << note << "\n";
  out << Headline(verdict) << "\n";
}

}  // namespace relplane::bench
