#pragma once
// One scenario through simulator, EM segmenter and mapper in one process, frame by frame, with
// the services' own message conversions in between (so the mapper sees what it sees live, with
// no bus and no clock), scored by the evaluation's metrics. Used by relplane-accuracy's seed
// sweeps and by the pipeline accuracy tests.

#include <cstdint>
#include <string>
#include <vector>

#include "relplane/accuracy/plane_errors.hpp"
#include "relplane/accuracy/world_kind.hpp"
#include "relplane/eval/map_metrics.hpp"
#include "relplane/eval/trajectory_metrics.hpp"

namespace relplane::accuracy {

// What to run: a scenario file and `--set key.path=value` overrides applied to it in order
// (a noise level or seed is `sim.sensor.noise_sigma=0.01`, `sim.sensor.seed=4`).
struct RunSpec {
  std::string file;
  std::vector<std::string> overrides;
  // True walls shorter than this are not scored (eval's VisibilityOptions::min_wall_length_m).
  double min_wall_length_m = 0.3;
  // Also keep each frame's segmented walls against the truth (RunResult::plane_errors).
  bool plane_errors = false;
};

// One frame's pose against the truth, for tracing where a run goes wrong.
struct FramePose {
  int64_t seq = 0;
  int status = -1;  // mapper::PoseStatus as int; -1: the frame was refused and has no pose
  double x = 0.0, y = 0.0, yaw = 0.0;                 // the estimate
  double true_x = 0.0, true_y = 0.0, true_yaw = 0.0;  // the simulator's
  int planes = 0;                                     // planes the pose used
};

struct RunResult {
  eval::TrajectoryMetrics trajectory;
  eval::MapMetrics map;
  // End errors of the true ends the best match reaches (within a quarter metre): a true wall
  // seen only in pieces is matched by one piece, whose far end lies metres from the wall's end.
  std::vector<double> reached_ends;
  int64_t frames = 0;
  int64_t lost_frames = 0;               // poses with status LOST
  int64_t motion_model_frames = 0;       // poses with status MOTION_MODEL (§II.E)
  int64_t rejected_frames = 0;           // a conversion refused the message: counted, not mapped
  int64_t rejected_odometry = 0;         // ODOMETRY readings refused (bad or out of order)
  std::vector<FramePose> poses;          // every frame's
  std::vector<PlaneError> plane_errors;  // with RunSpec::plane_errors: every frame's walls
  // Where each true wall of map.walls stands, seen from above (same order): which wall a run's
  // worst error is on.
  std::vector<geometry::Segment2> wall_segments;
  // Whether the walls in view fix every frame's pose (world_kind.hpp).
  WorldKind kind;
};

// Reads every section `spec` gives the services, as RunScenario does, and runs nothing. Throws as
// RunScenario.
void CheckScenario(const RunSpec& spec);

// The kind of world `spec` drives through (world_kind.hpp), from its true poses alone: nothing
// is sensed, segmented or mapped. Throws as RunScenario.
WorldKind ClassifyScenario(const RunSpec& spec);

// Runs `spec` to its last frame. Throws config::ConfigError with a one-line reason for a missing
// file, malformed YAML, a bad override or an invalid section (unknown key, wrong type), before
// any frame is made.
RunResult RunScenario(const RunSpec& spec);

}  // namespace relplane::accuracy
