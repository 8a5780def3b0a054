#pragma once
// Options of the Relative Plane mapper, one plain struct per component with defaults that hold
// for any indoor world and sensor (issue 4: "tune nothing to one scenario").

#include <cstdint>

namespace relplane::mapper {

// §II.A plane matching on the latest untransformed observation.
struct RegistrationOptions {
  int last_seen_window = 5;          // iterations; a plane unseen longer cannot match
  double max_angle = 0.2;            // rad between normals
  double max_distance = 0.3;         // m between plane offsets d
  double min_overlap = 0.3;          // of the shorter extent along the wall (and in height)
  double max_wall_normal_z = 0.3;    // |normal.z| above this is floor/ceiling: not a wall (2½D)
};

// §II.A end: backtracking / loop closure against the global map.
struct BacktrackOptions {
  bool enabled = true;
  double max_angle = 0.15;     // rad
  double max_distance = 0.25;  // m between the transformed plane and the mapped line
  double margin = 0.1;         // m the mapped extent is widened by for the overlap test
  double open_margin = 0.25;   // m the same beyond an end never seen static
  double min_overlap = 0.3;    // of the shorter extent
  // rad: for a wall known by its line only, how far the sighting may turn from it, besides the
  // blur of a short piece's fit (backtracking.cpp)
  double line_max_angle = 0.035;
};

// §II.B grouping.
struct GroupingOptions {
  int min_observations = 8;      // an ungrouped rltplane is processed once it has this many
  int ungrouped_timeout = 45;    // iterations; below min_observations by then: dropped
  int min_common = 8;            // iterations two rltplanes must share to count as co-visible
  int covisible_window = 60;     // co-visibility is counted over this many recent iterations
  int recent_groups = 3;         // a grouped plane not in the last few groups is "re-seen"
  // rad: an ungrouped rltplane whose orientation relative to a plane seen with it spreads more
  // than this (standard deviation over its last min_observations sightings) is not grouped yet
  double max_orientation_spread = 0.035;
};

// §II.C pairwise comparison and static edges.
struct ComparisonOptions {
  int min_samples = 10;            // iterations in a sub-interval to judge its static edges
  double static_std = 0.03;        // m: a pairing with a lower standard deviation is static
  double static_floor = 0.005;     // m: ... if also within static_ratio x the best pairing's,
  double static_ratio = 3.0;       //    or below static_floor
  double phase_hysteresis = 0.05;  // m: length change that flips growing <-> shrinking
  double parallel_angle = 0.17;    // rad: planes this close in orientation count as parallel
  int max_subinterval = 300;       // iterations; longer sub-intervals are closed (bounds cost)
  int freeze_lag = 90;             // iterations; sub-intervals older than this are frozen
  double min_motion = 0.05;        // m: edges must move this much in the sensor frame (std) for
                                   // a sub-interval to tell static from dynamic edges
};

// §II.D / §II.E localisation.
struct LocalisationOptions {
  double min_information = 0.5;  // smallest eigenvalue (m^-2 units) of the position system
                                 // for TRACKING; below it the motion model applies
  double prior_weight = 1e-4;    // weight of the previous position in the least squares
};

// Soft-linked groups (§V future work): least squares over the group placements at loop closure.
struct PoseGraphOptions {
  bool enabled = true;
  // rad, agreement of a shared plane's orientation in two groups. 0.005 until 2026-12-05: at
  // that, a loop's closing solve turned a 17.5 m leg by 0.16 degrees rather than move its
  // groups 2-3 cm along, and the next leg's walls went 6 cm across (loop_other_sensor, σ = 1 cm).
  double angle_sigma = 0.002;
  double position_sigma = 0.01;  // m, agreement of its line and static edge, plus the spread
                                 // of the static pairings that placed it (Placement::variance)
  // m (and rad): each group's placement as chained, weighed as the chain weighs its prior
  // against a line (localisation.prior_weight 1e-4: position_sigma / sqrt(1e-4)). At 100 m, a
  // gauge only, a direction the ties hardly observe slid by metres for a negligible gain.
  double prior_sigma = 1.0;
  // m and rad: agreement of the two poses of a loop closed by backtracking (PoseTie), the
  // motion model's over the few iterations the sensor sees neither side's wall ends; the same
  // for a group held where the chain put it from the one before (pose_graph.cpp ChainPriors).
  double pose_tie_sigma = 0.02;
  double pose_tie_angle_sigma = 0.01;
  int max_iterations = 10;
};

// §II.F reordering and regrouping, and how far back observations are kept for them. Ages are
// iterations since a group was made.
struct RegroupingOptions {
  bool enabled = true;
  int reorder_after = 150;  // the group's comparison order is chosen and kept from then on
  int regroup_after = 300;  // members with a comparison interval below min_interval are taken
                            // out: placed in another group, or dropped from the map
  int min_interval = 10;    // iterations a member must share with another one of its group
  int freeze_after = 900;   // the relative map is frozen; observations older than this (plus
                            // the co-visibility window) are dropped: regrouping cannot reach them
};

struct StartPose {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;  // sensor height; planes are mapped at sensor z + this
  double yaw = 0.0;
};

struct MapperOptions {
  RegistrationOptions registration;
  BacktrackOptions backtrack;
  GroupingOptions grouping;
  ComparisonOptions comparison;
  LocalisationOptions localisation;
  PoseGraphOptions graph;
  RegroupingOptions regrouping;
  StartPose start_pose;
  int max_observations = 3000;  // per rltplane, a hard cap besides the regrouping horizon
  // m: the published map draws a wall's end at the corner it meets when the crossing wall's
  // line passes this close (SnapEndsToCorners; about a ray spacing at the range limit); 0: off.
  double corner_radius = 0.1;
};

}  // namespace relplane::mapper
