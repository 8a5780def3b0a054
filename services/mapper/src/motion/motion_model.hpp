#pragma once
// §II.E the motion model: where the walls leave a direction open, the position along it moves on
// at a constant velocity learnt from the poses the walls fixed, or stands still while the sensor
// turns on the spot.

#include <cstdint>
#include <deque>

#include "motion/trajectory.hpp"
#include "relplane/common/geometry.hpp"
#include "relplane/mapper/odometry.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

struct Motion {
  geometry::Pose2 predicted;  // the last pose moved on at the learnt velocity or by odometry
  // Whether the motion is known: wheel odometry read it, a velocity was learnt from a stretch
  // of motion (not a turn on the spot), or the sensor is turning on the spot now (standing
  // still).
  bool known = false;
  // Wheel odometry read it: it knows whether the sensor moved on while turning, and `sigma`
  // (m, one sigma) is how far off it may be by now. A learnt velocity's drift is the pose
  // solver's (LearntVelocity).
  bool odometry = false;
  double sigma = 0.0;
  // rad per iteration: the heading's turn, learnt over the last iterations while the sensor
  // turns on the spot (0 otherwise); `predicted` keeps the last heading, the heading prior turns
  // on at this rate (Localiser).
  double yaw_rate = 0.0;
};

class MotionModel {
 public:
  // `max_step`: the farthest the platform moves in an iteration (LocalisationOptions::max_step).
  MotionModel(const MotionOptions& options, double max_step)
      : options_(options), max_step_(max_step) {}

  // The pose at `iteration`, from `last`, the pose of `last_iteration` (-1: none yet), and the
  // poses the walls fixed in `trajectory`.
  Motion Predict(const Trajectory& trajectory, const geometry::Pose2& last, int64_t last_iteration,
                 int64_t iteration) const;

  // Turning on the spot (the paths' corners): the heading is seen whatever the walls leave open,
  // and a sensor turning faster than MotionOptions::turn_rate is taken not to move on; faster by
  // more than twice the heading's own error (`yaw_sigma`, PoseEstimate::yaw_sigma), so that a
  // heading from a door jamb alone, wobbling frame to frame, does not pass for a turn.
  bool Turning(const geometry::Pose2& from, const geometry::Pose2& to, int64_t iterations,
               double yaw_sigma = 0.0) const;

  // Wheel odometry instead of the learnt velocity, when the robot has it (ODOMETRY): `last`
  // moved on by the motion it read since the previous iteration. Its error accumulates from
  // the increments' covariance and MotionOptions::odometry_drift of the distance driven, until
  // the walls fix the position again (Fixed).
  Motion Odometry(const geometry::Pose2& last, const OdometryIncrement& increment);
  // The walls fixed the position in every direction (§II.D): odometry's error starts again.
  void Fixed();
  // Odometry's distance scale from the poses the walls fixed (§II.E: the motion model's
  // constant is estimated from the constrained frames): `pose`, fixed, ends a span since the
  // last such pose over which `driven` is odometry's motion read (in that pose's frame): a
  // scale error carries the position off along every stretch the walls leave open. Returns
  // whether the span was long enough to count (a shorter one goes on to the next fixed pose).
  bool CalibrateOdometry(const geometry::Pose2& from, const geometry::Pose2& pose,
                         const geometry::Pose2& driven);
  // The median ratio of the walls' distance to odometry's over the last spans, 1 until there
  // are kMinSpans.
  double OdometryScale() const { return odometry_scale_; }

 private:
  // The latest stretch of fixed poses long enough to learn a velocity from: [*i0, *i1].
  bool LearningStretch(const Trajectory& trajectory, const geometry::Pose2& last, int64_t* i0,
                       int64_t* i1) const;
  // The median step along the heading between consecutive fixed poses in [i0, i1].
  bool MedianStep(const Trajectory& trajectory, int64_t i0, int64_t i1, double* step) const;
  // The heading turned over the last iteration and over the last two; `rate` (rad per
  // iteration) is its turn over the last two.
  bool TurningOnTheSpot(const Trajectory& trajectory, const geometry::Pose2& last,
                        int64_t last_iteration, double* rate) const;

  MotionOptions options_;
  double max_step_;
  // Since the walls last fixed the position: the odometry increments' position variance
  // (m^2, the covariances' traces) and the distance they drove (m).
  double odometry_variance_ = 0.0;
  double odometry_distance_ = 0.0;
  // Odometry's scale: the ratios of the last spans (at most kSpans) and their median.
  static constexpr size_t kSpans = 31, kMinSpans = 5;
  std::deque<double> scale_ratios_;
  double odometry_scale_ = 1.0;
};

}  // namespace relplane::mapper
