#include "relplane/accuracy/baseline.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace relplane::accuracy {
namespace {

std::string Label(const std::string& scenario, uint64_t seed) {
  return scenario + " " + (seed > 0 ? std::to_string(seed) : std::string("(own seed)"));
}

std::string Metres(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f m", value);
  return buffer;
}

// A finite ATE counts towards a sum; a run with nothing to score does not.
double Summable(double ate) { return std::isfinite(ate) ? ate : 0.0; }

}  // namespace

std::vector<BaselineRun> ParseBaseline(const std::string& json) {
  // JSON is YAML's flow style, so the scenario reader's parser reads SweepJson's output.
  YAML::Node root;
  try {
    root = YAML::Load(json);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(std::string("not JSON: ") + e.what());
  }
  const YAML::Node runs = root.IsMap() ? root["runs"] : YAML::Node();
  if (!runs || !runs.IsSequence()) {
    throw std::runtime_error("no \"runs\" list: not a sweep written by relplane-accuracy --json");
  }
  std::vector<BaselineRun> out;
  out.reserve(runs.size());
  for (size_t i = 0; i < runs.size(); ++i) {
    const YAML::Node run = runs[i];
    try {
      BaselineRun b;
      b.scenario = run["scenario"].as<std::string>();
      b.seed = run["seed"].as<uint64_t>();
      b.meets_targets = run["meets_targets"].as<bool>();
      const YAML::Node ate = run["ate_rmse_m"];
      b.ate_rmse_m = ate.IsNull() ? std::numeric_limits<double>::quiet_NaN() : ate.as<double>();
      out.push_back(std::move(b));
    } catch (const YAML::Exception&) {
      throw std::runtime_error("run " + std::to_string(i + 1) +
                               " lacks scenario, seed, meets_targets or ate_rmse_m");
    }
  }
  return out;
}

std::vector<BaselineRun> ReadBaseline(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  try {
    return ParseBaseline(text.str());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

BaselineComparison CompareWithBaseline(const std::vector<BaselineRun>& baseline,
                                       const std::vector<SweepRun>& runs, double threshold_m) {
  std::map<std::pair<std::string, uint64_t>, const BaselineRun*> before;
  for (const BaselineRun& b : baseline) before[{b.scenario, b.seed}] = &b;
  BaselineComparison c;
  c.threshold_m = threshold_m;
  std::vector<RunChange> worse;
  for (const SweepRun& run : runs) {
    const auto it = before.find({run.scenario, run.seed});
    if (it == before.end()) {
      ++c.not_in_baseline;
      continue;
    }
    const BaselineRun& b = *it->second;
    const bool meets = run.misses.empty();
    RunChange change{run.scenario, run.seed, b.ate_rmse_m, run.result.trajectory.ate_rmse_m,
                     run.misses};
    ++c.common;
    c.meeting_before += b.meets_targets ? 1 : 0;
    c.meeting_after += meets ? 1 : 0;
    c.ate_sum_before_m += Summable(change.ate_before_m);
    c.ate_sum_after_m += Summable(change.ate_after_m);
    const double delta = change.ate_after_m - change.ate_before_m;
    if (delta < -threshold_m) ++c.better;
    if (delta > threshold_m) {
      ++c.worse;
      worse.push_back(change);
    }
    if (meets && !b.meets_targets) c.now_met.push_back(change);
    if (!meets && b.meets_targets) c.now_missed.push_back(std::move(change));
  }
  std::stable_sort(worse.begin(), worse.end(), [](const RunChange& x, const RunChange& y) {
    return x.ate_after_m - x.ate_before_m > y.ate_after_m - y.ate_before_m;
  });
  worse.resize(std::min<size_t>(worse.size(), 3));
  c.most_worse = std::move(worse);
  return c;
}

std::string ComparisonText(const BaselineComparison& c, const std::string& baseline_name) {
  std::string out = "against " + baseline_name + ", " + std::to_string(c.common) +
                    " runs in both: meeting " + std::to_string(c.meeting_before) + " -> " +
                    std::to_string(c.meeting_after) + ", ATE sum " + Metres(c.ate_sum_before_m) +
                    " -> " + Metres(c.ate_sum_after_m) + "\n";
  if (c.not_in_baseline > 0) {
    out += "  " + std::to_string(c.not_in_baseline) + " runs not in the baseline\n";
  }
  for (const RunChange& r : c.now_met) {
    out += "  now met: " + Label(r.scenario, r.seed) + " (ATE " + Metres(r.ate_before_m) + " -> " +
           Metres(r.ate_after_m) + ")\n";
  }
  for (const RunChange& r : c.now_missed) {
    std::string why;
    for (size_t i = 0; i < r.misses_after.size(); ++i) {
      why += (i ? "; " : "") + r.misses_after[i];
    }
    out += "  now missed: " + Label(r.scenario, r.seed) + " (ATE " + Metres(r.ate_before_m) +
           " -> " + Metres(r.ate_after_m) + "; " + why + ")\n";
  }
  char over[32];
  std::snprintf(over, sizeof over, "%.1f mm", 1000.0 * c.threshold_m);
  out += std::string("  ATE better by over ") + over + " on " + std::to_string(c.better) +
         " runs, worse on " + std::to_string(c.worse);
  for (size_t i = 0; i < c.most_worse.size(); ++i) {
    const RunChange& r = c.most_worse[i];
    out += std::string(i == 0 ? "; the most: " : ", ") + Label(r.scenario, r.seed) + " " +
           Metres(r.ate_before_m) + " -> " + Metres(r.ate_after_m);
  }
  return out + "\n";
}

}  // namespace relplane::accuracy
