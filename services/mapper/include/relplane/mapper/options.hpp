#pragma once
// Options of the Relative Plane mapper, one plain struct per component with defaults that hold
// for any indoor world and sensor (issue 4: "tune nothing to one scenario").

#include <cmath>
#include <cstdint>

namespace relplane::mapper {

// How far the segmenter's fit of a wall can be trusted beyond what its residuals say: every
// step that weighs an orientation (comparisons §II.C, group placement §II.D, the pose §II.E,
// the published map's merge) uses the same model.
struct FitOptions {
  // rad: orientation sigma every wall has whatever its fit says (the map's own error), so the
  // best-fitting walls do not take all the weight.
  double orientation_floor = 0.001;
  // m: a piece's fit is off by about this much over its length, so its orientation by
  // atan(piece_blur / length) (a 0.2 m piece beside a door jamb takes some of the jamb's points).
  double piece_blur = 0.03;
};

// How an rltplane follows its visible length (§II.C: growth phases, the plane's maximum size).
struct RltPlaneOptions {
  // length-noise sigmas: a change smaller than this (or comparison.phase_hysteresis) never
  // turns the plane from growing to shrinking.
  double noise_hysteresis = 3.0;
  int smoothing = 5;      // sightings whose visible lengths are averaged for the phase (>= 3)
  int noise_window = 50;  // sightings the length noise is averaged over
  int full_length_sightings = 300;  // whole sightings the full length is the median of
  int retired_lengths = 64;         // lengths of dropped whole sightings kept (a thinned sample)
};

// The sensor's view as the mapper learns it from the edges and walls reported (§II.C: an edge
// cut by the view is not a wall's end). The histograms' resolution (0.5 degree, 2 cm) is fixed.
struct ViewOptions {
  double bearing_margin = 0.035;  // rad: an edge this close inside the learnt field of view is cut
  int min_pile = 20;  // edges in one bearing (or range) bin before a pile-up there counts
  // A range pile counts where its peak holds pile_contrast times the mean bin of the 0.5 m below
  // it, and at most one edge in pile_beyond_ratio lies beyond it.
  double pile_contrast = 5.0;
  int pile_beyond_ratio = 50;
  int min_support = 500;  // points: thinner walls say too little of the angular step
  int min_walls = 30;     // walls observed before the angular step is learnt
};

// §II.A plane matching on the latest untransformed observation.
struct RegistrationOptions {
  int last_seen_window = 5;        // iterations; a plane unseen longer cannot match
  double max_angle = 0.2;          // rad between normals
  double max_distance = 0.3;       // m between plane offsets d
  double min_overlap = 0.3;        // of the shorter extent along the wall (and in height)
  double max_wall_normal_z = 0.3;  // |normal.z| above this is floor/ceiling: not a wall (2½D)
  // m: an end seen this far from where it last was is another end: poses a few seconds apart
  // agree to centimetres and a wall end moves continuously, while a piece's door-side end lies a
  // door's width or more from the wall's.
  double end_jump = 0.5;
  int end_memory = 90;  // iterations an uncut end's sighting is compared against
  // m: a plane's end lies on another plane's line to this: a few times the edges' noise, and
  // well below a wall's thickness (a jamb, a recess).
  double same_surface = 0.05;
  // rad: a nearer plane's edge this close in bearing is on the same line of sight (an edge
  // behind it is occluded, not a wall end).
  double occlusion_bearing = 0.0175;
  double occlusion_nearer = 0.05;  // m: ... when it is at least this much nearer
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
  // m: of two parallel planes of one frame that both pass the tests for a mapped wall, one nearer
  // its line by more than this is the wall and the other a surface beside it (a few times a
  // line's noise, well below a jamb's or a recess's depth)
  double same_surface = 0.05;
};

// §II.B grouping.
struct GroupingOptions {
  int min_observations = 8;    // an ungrouped rltplane is processed once it has this many
  int ungrouped_timeout = 45;  // iterations; below min_observations by then: dropped
  int min_common = 8;          // iterations two rltplanes must share to count as co-visible
  int covisible_window = 60;   // co-visibility is counted over this many recent iterations
  int recent_groups = 3;       // a grouped plane not in the last few groups is "re-seen"
  // rad: an ungrouped rltplane whose orientation relative to a plane seen with it spreads more
  // than this (standard deviation over its last min_observations sightings) is not grouped yet
  double max_orientation_spread = 0.035;
  // iterations an ungrouped rltplane must share with the plane it is judged against for its
  // orientation spread to be judged at all
  int min_common_orientation = 4;
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
  double uncut_share = 0.8;        // of a sub-interval's samples, for an edge to be judged
  // m: a static pairing's spread, against which it is discounted when the chain is chosen (§II.F)
  double spread_scale = 0.005;
  // sin of the angle: two lines this close in orientation are parallel in a relative map
  double parallel_sin = 0.17;
  // m: a parallel piece's line pooled over sub-intervals too short to judge (min_samples in all)
  // is read only if its offsets agree this closely (parallel fits agree to millimetres).
  double pooled_std = 0.01;
  // m: a wall end's position along its wall is known to about this (one sigma) however often it
  // is seen: where the segmenter's last column on the wall fell, a column spacing or more either
  // side of a corner. A member's line placed through a crossing wall's end is known to this, and
  // its parallel members' lines are weighed against it (relative_refine.cpp, §II.D).
  double edge_along_std = 0.02;
};

// §II.D placing a group on the global map: its prior (its members as seen around when it was
// made) and how its links' lines and static edges are weighed.
struct GlobalMapOptions {
  // m: a wall end seen from two fixed poses in a row moves less than this if it is the end
  double end_still = 0.05;
  // m: a wall end's first and latest sightings agree this well if they are the same end (the
  // end's noise and the pose's drift since the start)
  double first_end_agreement = 0.2;
  // m: a sighting's middle this far from the line the others agree on is not the same wall
  double line_agreement = 0.1;
  // m: a fixed pose's error across a wall, added to each sighting's own offset error so that
  // the best-fitting sighting does not take all the weight
  double pose_noise = 0.01;
  // cos of the angle: a member's normal this near a direction the other members' lines leave
  // open spans it
  double spans_open = 0.7071;
  // Weighing a link's line: the offset noise of a fitted line where its points are (m), and
  // how well a line must be known to count fully (m); a short piece's orientation bias is the
  // comparison's piece blur (comparison.hpp)
  double line_noise = 0.01;
  double full_line = 0.03;
  // m: a link's static edge further than this along its wall from where the group's prior puts
  // it is not taken while another link's edge agrees with the prior (a wrongly paired edge is a
  // wall's length or a door's width off; the prior is off by centimetres to decimetres)
  double edge_gate = 0.5;
  // rad^-2: the chained orientation as a gauge only, for planes no comparison links to the held
  // ones (a comparison's information is 1e2-1e5)
  double chained_orientation_prior = 1.0;
};

// §II.D / §II.E localisation.
struct LocalisationOptions {
  double min_information = 0.5;  // smallest eigenvalue (m^-2 units) of the position system
                                 // for TRACKING; below it the motion model applies
  double prior_weight = 1e-4;    // weight of the previous position in the least squares
  double outlier = 0.3;          // m: a wall this far from its line is left out
  // m: a wall fitting the pose worse than `suspect` is tried without; left out where the rest,
  // without it, fit within `suspect` and put it further off than `misregistered`: more than a
  // map's error, less than the depth of a pilaster or a recess beside a wall.
  double suspect = 0.05;
  double misregistered = 0.15;
  // m per iteration: how far a learnt velocity may carry the position off in an iteration.
  double drift_rate = 0.002;
  // m: how far off the prediction may be an iteration after a pose that wall ends fixed along
  // the walls.
  double tracked_prediction = 0.01;
  double end_gate = 0.1;  // m: the motion model (§II.E) snaps to a mapped end this close
  // cos of the angle: an open direction this near the heading is one the sensor may move along.
  double along_heading = 0.7071;
  // m: the farthest the platform moves in an iteration (3 m/s at 30 Hz): what a learnt velocity
  // is capped at, and how far ahead of the previous pose a wall end may put it when no motion
  // is known (a step for each iteration the position has been held still, up to max_held).
  double max_step = 0.1;
  int max_held = 5;
  // m^-2: information (smallest eigenvalue of the sum of n n^T over unit wall normals) below
  // which walls leave a direction open: lines within about 11 degrees of parallel
  double open_information = 0.02;
  // m: a wall end's position noise (2 sigma) where its samples lie close together: a mapped
  // end and a static edge seen now are held to it, and a line's unit weight stands for it
  double edge_noise = 0.03;
  // sigmas: where the walls leave the position open, their heading and the motion model's are
  // weighed together unless this many combined sigmas apart (then the motion changed).
  double heading_gate = 3.0;
};

// §II.E the motion model: a constant velocity learnt from the poses the walls fixed.
struct MotionOptions {
  // rad per iteration (17 deg/s at 30 Hz): turning faster than this (by more than twice the
  // heading's own error) is turning on the spot, and the sensor is taken not to move on.
  double turn_rate = 0.01;
  int window = 15;        // iterations the velocity is averaged over
  int min_span = 10;      // iterations: the shortest stretch of fixed poses it is learnt from
  int max_gap = 30;       // iterations lost in a row beyond which nothing is predicted
  int max_stretches = 8;  // stretches looked back over, each one too short
  // iterations after the last pose mapped walls placed through which a frame with no mapped
  // wall in view still gets the learnt motion's pose (half a second at 30 Hz)
  int max_coast = 15;
  int pose_history = 2000;  // iterations of poses kept
  // Wheel odometry (ODOMETRY, optional): one sigma of its error per metre driven on top of the
  // covariance it reports, which leaves out the systematic errors (wheel radii, track width;
  // a calibrated robot's are about 1 %). How far an odometry prediction may be off grows with
  // both since the walls last fixed the position.
  double odometry_drift = 0.02;
  // m: odometry's distance scale is learnt from spans at least this long between poses the walls
  // fixed (the walls' distance over odometry's), as the median of the last spans' ratios.
  double odometry_scale_span = 0.5;
};

// Soft-linked groups (§V future work): least squares over the group placements at loop closure.
struct PoseGraphOptions {
  bool enabled = true;
  // rad, agreement of a shared plane's orientation in two groups: tight enough that a loop's
  // closing solve moves groups along rather than turn a long leg.
  double angle_sigma = 0.002;
  double position_sigma = 0.01;  // m, agreement of its line and static edge, plus the spread
                                 // of the static pairings that placed it (Placement::variance)
  // m (and rad): each group's placement as chained, weighed as the chain weighs its prior
  // against a line (localisation.prior_weight 1e-4: position_sigma / sqrt(1e-4)); a gauge only
  // lets a direction the ties hardly observe slide.
  double prior_sigma = 1.0;
  // m and rad: agreement of the two poses of a loop closed by backtracking (PoseTie), the
  // motion model's over the few iterations the sensor sees neither side's wall ends; the same
  // for a group held where the chain put it from the one before (pose_graph.cpp ChainPriors).
  double pose_tie_sigma = 0.02;
  double pose_tie_angle_sigma = 0.01;
  int max_iterations = 10;
  double robust = 3.0;  // sigmas: the Cauchy kernel's scale
  // sigmas: without a loop closed by backtracking, a solve runs only where the chained
  // placements leave some tie further off than this (shared planes the chain already holds
  // within the ties' noise have no error to spread).
  double consistent = 3.0;
  double initial_damping = 1e-3;  // Levenberg-Marquardt, relative to the diagonal
  // A loop that closes where the chain already has the sensor has nothing to spread: no tie
  // unless the pose jumps by at least this much (m) or turns by this much (rad).
  double tie_min_jump = 0.005;
  double tie_min_turn = 0.002;
  int max_pose_ties = 1000;  // the latest kept (a few per loop driven; bounded for long runs)
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
  int sweep_period = 64;    // iterations between sweeps dropping old observations of every plane
};

// The published map (MAP): duplicate walls merged, ends drawn at corners.
struct PublishedMapOptions {
  // m: a wall's end is drawn at the corner it meets when the crossing wall's line passes this
  // close (about a ray spacing at the range limit); 0: off.
  double corner_radius = 0.1;
  double merge_angle = 0.05;    // rad: walls this close in orientation (and offset) are merged
  double merge_distance = 0.1;  // m
  // m: two walls on one line sharing more than this where the two ends in the shared stretch were
  // not both seen as wall ends are one wall seen in two stretches.
  double cut_overlap = 0.2;
  // A wall end moves to a corner only inside the wall by up to this many corner radii, and by
  // at most this fraction of the wall's length from each end.
  double min_shortened_radii = 2.0;
  double max_shortened_fraction = 0.25;
  // rad: crossing walls closer than this to parallel make no corner (where their lines cross
  // moves far with a small error in either orientation)
  double min_corner_angle = 30.0 * M_PI / 180.0;
};

struct StartPose {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;  // sensor height; planes are mapped at sensor z + this
  double yaw = 0.0;
};

struct MapperOptions {
  FitOptions fit;
  RltPlaneOptions rltplane;
  ViewOptions view;
  RegistrationOptions registration;
  BacktrackOptions backtrack;
  GroupingOptions grouping;
  ComparisonOptions comparison;
  GlobalMapOptions global_map;
  LocalisationOptions localisation;
  MotionOptions motion;
  PoseGraphOptions graph;
  RegroupingOptions regrouping;
  PublishedMapOptions published_map;
  StartPose start_pose;
  int max_observations = 3000;  // per rltplane, a hard cap besides the regrouping horizon
};

}  // namespace relplane::mapper
