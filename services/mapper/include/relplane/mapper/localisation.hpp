#pragma once
// §II.D current position from the present untransformed observations against the global map,
// and §II.E the motion model when only one partial plane is in view.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "relplane/common/geometry.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/state.hpp"

namespace relplane::mapper {

enum class PoseStatus { kTracking, kMotionModel, kInitializing, kLost };

struct PoseEstimate {
  geometry::Pose2 pose;
  PoseStatus status = PoseStatus::kLost;
  int planes = 0;  // planes used
  // The §II.E motion model moved the position along the heading to a wall end seen uncut from
  // poses the walls fixed (no motion known, walls leaving that direction open).
  bool end_moved = false;
  // rad: how far off the heading may be (the walls' fit sigmas and short-piece bias combined).
  double yaw_sigma = 0.0;
  // What the walls' lines and ends in view fixed of the position, without the previous pose:
  // the sum of w d d^T over the solve's equations, weight 1 for a line good to
  // LearnedFrustum::kEdgeNoise (observability.hpp turns it into a covariance).
  Eigen::Matrix2d position_information = Eigen::Matrix2d::Zero();
};

// One observation of a mapped wall: what is seen now and where the map has it.
struct Sighting {
  const Observation* obs = nullptr;
  const RltPlane* plane = nullptr;
  Placement world;
  // Where each end of the wall stood when seen uncut from poses the walls fixed (the median of
  // those sightings): for the §II.E motion model, a wall end the map does not place yet.
  bool end_seen[2] = {false, false};
  Eigen::Vector2d end[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
};

// The sensor's view as learned from the edges it reports. Edges cut by the view pile up at one
// bearing (every wall crossing the border gives one, every frame), while wall ends spread over
// all bearings: the field of view is the most frequent bearing among the widest ones. The
// widest bearing alone would do without noise, but one noisy edge close by widens it for good
// and the cut edges then pass for wall ends. The range limit is learned the same way, from the
// farthest pile-up of edge distances with next to nothing beyond it (not the fullest: a wall end
// seen while turning in place piles up too): in a small world no wall reaches the range and
// nothing piles up there, so no limit is learned. An edge near either limit is cut by the view,
// not a wall's end (a sensor turning in place sees a range-cut edge stand still, like a wall
// end).
class LearnedFrustum {
 public:
  void Observe(const Eigen::Vector2d& edge);
  // The half field of view: the pile-up's upper bin edge once it stands out, else the widest.
  double Limit() const;
  // The range limit, or infinity while none stands out.
  double RangeLimit() const;
  bool Clipped(const Eigen::Vector2d& edge) const;
  // The same for a wall's edge, `other` its other edge: also cut where the wall runs on past it
  // and reaches the range within the bearing margin (rays grazing a wall sample it sparsely,
  // and the last sample in range may lie well short of the limit).
  bool Clipped(const Eigen::Vector2d& edge, const Eigen::Vector2d& other) const;
  static constexpr double kEdgeNoise = 0.03;  // m, a wall end's position noise (2 sigma)
  // The sensor's angular sampling step, learnt from the walls seen: a wall's solid angle over
  // the points that support it is the solid angle per ray. Nought until enough are seen.
  void ObserveSampling(const Observation& obs);
  double AngularStep() const;
  // How far apart the sensor's samples land along a wall at its edge `edge` (sensor frame), the
  // wall's line `d` from the sensor: the step times r^2 / d. Nought while the step is unknown.
  double EdgeSpacing(const Eigen::Vector2d& edge, double d) const;

 private:
  static constexpr double kBearingMargin = 0.035;  // rad (2 degrees)
  static constexpr double kBinWidth = 0.0087;      // rad (0.5 degrees)
  static constexpr int kBins = 362;                // up to pi
  static constexpr double kRangeBin = 0.02;        // m
  static constexpr int kRangeBins = 2500;          // up to 50 m
  static constexpr int kMinPile = 20;
  void UpdateRangeLimit();
  double max_bearing_ = 0.0;
  int counts_[kBins] = {};
  int mode_bin_ = 0;
  std::vector<int> range_counts_ = std::vector<int>(kRangeBins, 0);
  int max_range_bin_ = 0;
  int observed_ = 0;
  double range_limit_ = std::numeric_limits<double>::infinity();
  // Per observation, log of its solid angle per supporting point over bins of kStepBin.
  static constexpr double kStepBin = 0.02;
  static constexpr int kStepBins = 600;  // exp(-18) to exp(-6) sr: steps of 0.12 mrad to 50 mrad
  static constexpr double kStepLogMin = -18.0;
  std::vector<int> step_counts_ = std::vector<int>(kStepBins, 0);
  int steps_observed_ = 0;
  double step_ = 0.0;
};

// How far apart a sensor with `step` rad between its rays lands its samples along a wall at its
// edge `edge` (from the sensor), the wall's line `d` from the sensor: step r^2 / d. Nought while
// the step is not known (not positive).
double EdgeSpacing(double step, const Eigen::Vector2d& edge, double d);

// The standard deviation (rad) of an observed wall's orientation from its own fit: a line
// fitted to `support` points spread evenly over the visible length L with residual `rms` has
// slope variance rms^2 / (support L^2 / 12). Zero for an exact fit (rms 0), infinite when there
// are too few points to tell.
double OrientationSigma(const Observation& obs);

// The weight 1 / (sigma^2 + floor^2) an observed wall's orientation gets from OrientationSigma,
// with a floor (the map's own error) so the best-fitting walls do not take all the weight.
double OrientationWeight(const Observation& obs);

// The same weight for a mapped wall from the best fit among its kept observations: how far its
// orientation can be trusted when a group is turned onto the map (a door jamb or a sliver of
// wall seen over a few centimetres must not turn walls metres long).
double OrientationWeight(const RltPlane& plane);

// The farthest the platform moves in an iteration (3 m/s at 30 Hz): what a learnt velocity is
// capped at, and how far ahead of the previous pose a wall end may put it when no motion is known
// (a step for each iteration the position has been held still, up to kMaxHeld of them).
constexpr double kMaxStep = 0.1;  // m
constexpr int kMaxHeld = 5;

// Information (smallest eigenvalue of the sum of n n^T over unit wall normals) below which
// walls leave a direction open: lines within ~11 degrees of parallel.
constexpr double kOpenInformation = 0.02;

// Least squares a x = b for a position, with `previous` as a weak prior (weight `prior_weight`,
// applied when the smallest information is below `min_information`). Along a direction the
// equations leave open (walls within ~11 degrees of parallel) the previous position is kept as
// it is: their lines' millimetre disagreements would otherwise move it by centimetres, through
// the slight angle between them, every time it is solved.
Eigen::Vector2d SolveWithPrior(const Eigen::Matrix2d& a, const Eigen::Vector2d& b,
                               const Eigen::Vector2d& previous, double prior_weight,
                               double min_information);

// Solves the sensor pose: yaw from the mean orientation difference (weighted by
// OrientationSigma, so a short noisy wall such as a door jamb does not turn the heading),
// position by least squares over the walls' lines (one equation each: the middle of the part in
// view lies on the mapped line, where the fit is good) and their static edges
// seen now (one more each, along the wall; with the motion known, weighed against `previous`
// there), with `previous` as a weak prior elsewhere. With a single
// wall, or walls that leave the position underdetermined, the result is the motion model
// (§II.E): the wall stays where the map has it, the unobserved direction keeps its previous
// value, and a mapped wall end seen at its predicted place pins the position along the wall.
// `held`: the iterations in a row before this one in which no motion was known and no wall end
// moved the position (`end_moved`): the sensor may have moved on a step in each.
// `predicted_for`: where `previous` is a learnt velocity's prediction, the iterations it has
// carried the position since the walls last fixed it; 0 where no motion is known.
PoseEstimate Localise(const std::vector<Sighting>& sightings, const geometry::Pose2& previous,
                      const LearnedFrustum& frustum, const LocalisationOptions& options,
                      int held = 0, int predicted_for = 0);

}  // namespace relplane::mapper
