#pragma once
// Options of the evaluation (scenario section `logger`) and the expected outcome (top-level
// `expect:`). Plain structs with defaults; services/logger/shell/options_yaml fills them from
// YAML.

#include <string>
#include <vector>

namespace relplane::eval {

// When a mapped wall counts as the same wall as a true one (both seen from above as segments).
struct MatchOptions {
  double angle_max_deg = 10.0;  // normals' angle, sign-agnostic
  double offset_max_m = 0.3;    // mapped segment's midpoint to the true wall's line
  double overlap_min_m = 0.2;   // shared length along the true wall
};

// Which true walls the robot could have seen: a wall is expected when a point of it lies within
// range and field of view of some truth pose, with no other true wall in between, or when a
// mapped wall matches it. Defaults mirror the simulator's depth sensor.
struct VisibilityOptions {
  double range_m = 8.0;
  double hfov_deg = 90.0;
  double sample_step_m = 0.25;     // spacing of the points tested along each wall
  double min_wall_length_m = 0.3;  // shorter true walls are ignored by the map metrics
};

struct EvalOptions {
  MatchOptions match;
  VisibilityOptions visibility;
  double rpe_segment_m = 1.0;   // path length of the relative pose error's segments
  double flush_period_s = 1.0;  // how often the logger rewrites the run folder (when changed)
  double svg_width_px = 900.0;
};

// One line of `expect:`: a metric (see expectations.hpp for the keys) and its limit.
struct Expectation {
  std::string key;
  double limit = 0.0;
};

}  // namespace relplane::eval
