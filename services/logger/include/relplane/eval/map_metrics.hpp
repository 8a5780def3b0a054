#pragma once
// Map accuracy: the mapped walls (MAP) against the true walls (SIM_WORLD), both seen from above
// as segments in the x-y plane.

#include <cstdint>
#include <vector>

#include "relplane/common/geometry.hpp"
#include "relplane/eval/options.hpp"
#include "relplane/eval/trajectory_metrics.hpp"
#include "relplane/eval/types.hpp"

namespace relplane::eval {

// A vertical plane seen from above: its line n . p + offset = 0 (unit n) and the extent of its
// vertices along that line.
struct WallLine {
  int64_t id = 0;
  geometry::Segment2 segment;
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  double offset = 0.0;
  double z_min = 0.0;  // vertical extent of the vertices
  double z_max = 0.0;
};

// Walls are the planes with |normal.z| < 0.1 (DESIGN: scenario conventions) whose vertices span
// a segment. `without_extent` (optional) counts walls with fewer than two distinct vertices.
std::vector<WallLine> WallsOf(const std::vector<PlaneRecord>& planes,
                              int64_t* without_extent = nullptr);

// The sensor's height: the median z of the truth poses (NaN without any).
double SensorHeight(const std::vector<PoseSample>& truth);

// Whether the wall spans height `z` (always true for a NaN z). A 2½D sensor at z sees a wall
// only there: a lintel above a door neither counts as a wall nor hides one.
bool SpansHeight(const WallLine& wall, double z);

// The matching of one true wall.
// A true wall counts as mapped when its matches cover at least this fraction of its visible
// length: a plane over a few centimetres of a long wall does not map it.
constexpr double kMappedCoverageMin = 0.5;

struct WallMatch {
  int64_t true_id = 0;
  double length_m = 0.0;
  bool expected = false;            // seen from the truth trajectory, or matched
  std::vector<int64_t> mapped_ids;  // every mapped plane matched to it, best first
  double visible_length_m = 0.0;    // seen from the truth trajectory
  double mapped_length_m = 0.0;     // under the union of its matches
  double coverage = 0.0;  // fraction of the visible length its matches cover (of the length
                          // when no part was seen)
  bool mapped = false;    // coverage >= kMappedCoverageMin
  double normal_error_deg = kNaN;  // of the best match
  double offset_error_m = kNaN;    // best match's midpoint to the true line
  // True ends to the outermost ends of all its matches together, in wall order; NaN for an
  // end the truth trajectory never saw.
  double endpoint_error_m[2] = {kNaN, kNaN};
  double overlap_m = kNaN;
};

struct ErrorSummary {
  double mean = kNaN;
  double max = kNaN;
};

struct MapMetrics {
  bool has_truth = false;  // a SIM_WORLD was received
  int64_t true_walls = 0;  // long enough to count (VisibilityOptions)
  int64_t expected_walls = 0;
  int64_t mapped_planes = 0;
  int64_t mapped_walls = 0;
  int64_t mapped_without_extent = 0;
  int64_t walls_mapped = 0;   // true walls covered over kMappedCoverageMin of their visible length
  int64_t partly_mapped = 0;  // true walls with matches covering less (counted as missed too)
  // Extra matches covering part of the wall a better match facing the same way covers.
  int64_t duplicates = 0;
  // Extra matches covering only parts that better matches facing the other way cover: the
  // wall's other face.
  int64_t other_faces = 0;
  int64_t fragments = 0;       // extra matches covering only parts no better match covers
  int64_t spurious = 0;        // mapped walls matching no true wall
  int64_t on_short_walls = 0;  // mapped walls on true walls too short to score (door jambs)
  int64_t missed = 0;          // expected true walls not mapped
  ErrorSummary normal_error_deg;
  ErrorSummary offset_error_m;
  ErrorSummary endpoint_error_m;
  std::vector<WallMatch> walls;
  std::vector<int64_t> spurious_ids;
};

// `truth` is the true trajectory, for deciding which walls were in view.
MapMetrics ComputeMapMetrics(const MapSnapshot& world, const MapSnapshot& map,
                             const std::vector<PoseSample>& truth, const EvalOptions& options);

// Whether a point of `wall` was within range and field of view of some pose, with no other wall
// of `walls` crossing the line of sight.
bool WallSeenFrom(const WallLine& wall, const std::vector<WallLine>& walls,
                  const std::vector<PoseSample>& poses, const VisibilityOptions& options);

}  // namespace relplane::eval
