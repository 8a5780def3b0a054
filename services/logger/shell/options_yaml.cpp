#include "options_yaml.hpp"

#include <fstream>
#include <sstream>

#include "relplane/common/options.hpp"
#include "relplane/eval/expectations.hpp"

namespace relplane::eval {
namespace {

void ReadPositive(config::Reader& r, const std::string& key, double* value) {
  r.Read(key, value);
  if (!(*value > 0.0)) r.Fail(key, "must be > 0");
}

// The simulated sensor's range and field of view, when the scenario has one: what the run
// could see. The simulator checks its own section.
VisibilityOptions SensorVisibility(const std::string& yaml, const std::string& name) {
  VisibilityOptions v;
  config::Reader sensor = config::Reader::FromString(yaml, name, "sim").Child("sensor");
  sensor.Read("max_range", &v.range_m);
  sensor.Read("hfov_deg", &v.hfov_deg);
  return v;
}

EvalOptions ReadOptions(config::Reader r, const VisibilityOptions& visibility) {
  EvalOptions o;
  o.visibility = visibility;
  ReadPositive(r, "flush_period_s", &o.flush_period_s);
  ReadPositive(r, "rpe_segment_m", &o.rpe_segment_m);
  ReadPositive(r, "svg_width_px", &o.svg_width_px);
  config::Reader match = r.Child("match");
  ReadPositive(match, "angle_max_deg", &o.match.angle_max_deg);
  ReadPositive(match, "offset_max_m", &o.match.offset_max_m);
  ReadPositive(match, "overlap_min_m", &o.match.overlap_min_m);
  config::Reader vis = r.Child("visibility");
  ReadPositive(vis, "range_m", &o.visibility.range_m);
  ReadPositive(vis, "hfov_deg", &o.visibility.hfov_deg);
  if (o.visibility.hfov_deg > 360.0) vis.Fail("hfov_deg", "must be <= 360");
  ReadPositive(vis, "sample_step_m", &o.visibility.sample_step_m);
  vis.Read("min_wall_length_m", &o.visibility.min_wall_length_m);
  r.Finish();
  return o;
}

std::vector<Expectation> ReadExpect(config::Reader r) {
  std::vector<Expectation> expect;
  for (const ExpectationKey& k : ExpectationKeys()) {
    if (!r.Has(k.key)) continue;
    Expectation e{k.key, 0.0};
    r.Read(k.key, &e.limit);
    expect.push_back(e);
  }
  r.Finish();
  return expect;
}

}  // namespace

EvalConfig LoadEvalConfig(const std::string& file) {
  // Read once: the file may be a pipe, and both sections must come from the same text.
  std::ifstream in(file);
  if (!in) throw config::ConfigError(file + ": cannot open the file");
  std::stringstream text;
  text << in.rdbuf();
  return ParseEvalConfig(text.str(), file);
}

EvalConfig ParseEvalConfig(const std::string& yaml, const std::string& name) {
  EvalConfig c;
  c.options =
      ReadOptions(config::Reader::FromString(yaml, name, "logger"), SensorVisibility(yaml, name));
  c.expect = ReadExpect(config::Reader::FromString(yaml, name, "expect"));
  return c;
}

}  // namespace relplane::eval
