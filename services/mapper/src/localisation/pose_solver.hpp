#pragma once
// §II.D the sensor pose from the walls in view against where the map has them, and §II.E the
// motion model when they leave a direction open.

#include <Eigen/Core>
#include <vector>

#include "global_map/placement.hpp"
#include "localisation/frustum.hpp"
#include "localisation/least_squares.hpp"
#include "plane_store/rltplane.hpp"
#include "relplane/common/geometry.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/types.hpp"

namespace relplane::mapper {

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

// What `previous` stands for in the pose solver (§II.E): the last pose held still (not known),
// or a prediction by a learnt velocity or wheel odometry, good to `sigma` along a direction the
// walls leave open.
struct Prediction {
  bool known = false;
  double sigma = 0.0;  // m, one sigma
};

// §II.E the heading the motion model expects: the last heading, turned on at the rate of a turn
// on the spot, good to `sigma` (rad, one sigma; 0: no prior).
struct HeadingPrior {
  double yaw = 0.0;
  double sigma = 0.0;
};

// A learnt velocity's prediction `iterations` after the walls last fixed the position: it drifts
// by up to LocalisationOptions::drift_rate an iteration. Not known for 0 iterations.
Prediction LearntVelocity(int iterations, const LocalisationOptions& options);

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
// `prediction`: where `previous` is the motion model's prediction (a learnt velocity or wheel
// odometry), how far off it may be by now; unknown where `previous` is the last pose held.
// `heading_prior`: where the walls leave the position open (the motion model's case), their
// heading is weighed against this prior by the two sigmas, unless they disagree by more than
// LocalisationOptions::heading_gate combined sigmas (the motion changed); yaw_sigma is then the
// combined one. A lone sliver of a wall fitted degrees off turns the pose by what it shows
// beyond the prior's error, not by all of it.
PoseEstimate Localise(const std::vector<Sighting>& sightings, const geometry::Pose2& previous,
                      const LearnedFrustum& frustum, const LocalisationOptions& options,
                      const FitOptions& fit, int held = 0, const Prediction& prediction = {},
                      const HeadingPrior& heading_prior = {});

}  // namespace relplane::mapper
