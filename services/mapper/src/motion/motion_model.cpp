#include "motion/motion_model.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

namespace relplane::mapper {

bool MotionModel::Turning(const geometry::Pose2& from, const geometry::Pose2& to,
                          int64_t iterations, double yaw_sigma) const {
  return std::abs(std::remainder(to.yaw - from.yaw, 2.0 * M_PI)) >
         options_.turn_rate * static_cast<double>(iterations) + 2.0 * yaw_sigma;
}

bool MotionModel::LearningStretch(const Trajectory& trajectory, const geometry::Pose2& last,
                                  int64_t* i0_out, int64_t* i1_out) const {
  // A fixed pose or two after a long spell of the motion model is no stretch, and must not make
  // the velocity unknown: the stretch before it still tells it, as long as the heading has not
  // turned since (moving off after a turn on the spot, the motion is not known).
  const std::set<int64_t>& fixed = trajectory.fixed;
  const auto& poses = trajectory.poses;
  int64_t i1 = *fixed.rbegin(), i0 = i1;
  for (int stretch = 0;; ++stretch) {
    i0 = *fixed.lower_bound(i1 - options_.window);
    auto p0 = poses.find(i0), p1 = poses.find(i1);
    if (p0 == poses.end() || p1 == poses.end()) return false;
    if (stretch > 0 && Turning(p1->second, last, options_.min_span)) return false;
    // Fixed poses must be consecutive enough to be one stretch of motion.
    const auto in_stretch =
        static_cast<int64_t>(std::distance(fixed.lower_bound(i0), fixed.upper_bound(i1)));
    if (i1 - i0 >= options_.min_span && in_stretch >= (i1 - i0) / 2) break;
    const auto first = fixed.find(i0);
    if (first == fixed.begin() || stretch + 1 >= options_.max_stretches) return false;
    i1 = *std::prev(first);
  }
  *i0_out = i0;
  *i1_out = i1;
  return true;
}

bool MotionModel::MedianStep(const Trajectory& trajectory, int64_t i0, int64_t i1,
                             double* step) const {
  // The median of the steps between consecutive fixed poses, not the way from the first to the
  // last: a fixed pose that the walls set right is not motion. Nor a step taken while turning on
  // the spot (judged over the iterations either side, as a heading from short walls wobbles by
  // a turn's step from one iteration to the next): the sensor stands still there, and the
  // stretch that ends a turn and starts the next leg would learn the leg's speed as the median
  // of the turn's noughts and the leg's first steps (§II.E). A stretch that is all turn stood
  // still.
  const std::set<int64_t>& fixed = trajectory.fixed;
  const auto& poses = trajectory.poses;
  std::vector<double> steps;
  bool turned = false;
  for (auto k = fixed.lower_bound(i0); k != fixed.end() && *k < i1; ++k) {
    const int64_t j = *std::next(k);
    auto a = poses.find(*k), b = poses.find(j);
    if (j - *k > 2 || a == poses.end() || b == poses.end()) continue;
    auto before = poses.find(*k - 1), after = poses.find(j + 1);
    if (before == poses.end()) before = a;
    if (after == poses.end()) after = b;
    if (Turning(before->second, after->second, after->first - before->first)) {
      turned = true;
      continue;
    }
    const Eigen::Vector2d d = b->second.Rotation().inverse() *
                              (b->second.Translation() - a->second.Translation()) /
                              static_cast<double>(j - *k);
    steps.push_back(d.x());
  }
  if (steps.empty() && turned) steps.push_back(0.0);
  if (steps.empty()) return false;
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  *step = steps[steps.size() / 2];
  return true;
}

bool MotionModel::TurningOnTheSpot(const Trajectory& trajectory, const geometry::Pose2& last,
                                   int64_t last_iteration, double* rate) const {
  // A heading from short walls alone wobbles back and forth by more than a turn's step, but its
  // wobbles do not add up: the turn must show over the last two iterations as well.
  const auto& poses = trajectory.poses;
  auto before = poses.lower_bound(last_iteration - 1);
  if (before == poses.end() || before->first >= last_iteration ||
      !Turning(before->second, last, last_iteration - before->first)) {
    return false;
  }
  const auto turn = [&](const std::pair<const int64_t, geometry::Pose2>& from) {
    return std::remainder(last.yaw - from.second.yaw, 2.0 * M_PI) /
           static_cast<double>(last_iteration - from.first);
  };
  *rate = turn(*before);
  auto earlier = poses.lower_bound(before->first - 1);
  if (earlier == poses.end() || earlier->first >= before->first) return true;
  *rate = turn(*earlier);
  return Turning(earlier->second, last, last_iteration - earlier->first);
}

Motion MotionModel::Predict(const Trajectory& trajectory, const geometry::Pose2& last,
                            int64_t last_iteration, int64_t iteration) const {
  // Constant velocity in the sensor's frame, learnt from the poses the walls fixed in every
  // direction: where they leave one open (a hallway between door frames) the position along it
  // moves on instead of standing still as the motion model alone would.
  Motion out{last, false};
  if (last_iteration < 0 || iteration - last_iteration > options_.max_gap) return out;
  // The heading turns on at a turn's rate whether or not a velocity is learnt yet (the start,
  // turning on the spot).
  double rate = 0.0;
  const bool turning = TurningOnTheSpot(trajectory, last, last_iteration, &rate);
  if (turning) out.yaw_rate = rate;
  if (trajectory.fixed.empty()) return out;
  int64_t i0 = 0, i1 = 0;
  double median = 0.0;
  if (!LearningStretch(trajectory, last, &i0, &i1)) return out;
  if (!MedianStep(trajectory, i0, i1, &median)) return out;
  // A span of turning on the spot learns a velocity of nought, which says nothing of how the
  // sensor moves off once the turn ends (the paths' corners).
  out.known = !Turning(trajectory.poses.at(i0), trajectory.poses.at(i1), i1 - i0);
  // Only the part along the heading: the platform drives forwards (the paper's robot, the
  // simulator's paths), and a sideways part is the noise of the fixed poses, which would walk
  // the position off along an open direction.
  const Eigen::Vector2d step(std::clamp(median, -max_step_, max_step_), 0.0);
  // Turning on the spot, standing still is the motion.
  if (turning) {
    out.known = true;
    return out;
  }
  const double frames = static_cast<double>(iteration - last_iteration);
  const Eigen::Vector2d moved = last.Translation() + last.Rotation() * step * frames;
  out.predicted = {moved.x(), moved.y(), last.yaw};
  return out;
}

Motion MotionModel::Odometry(const geometry::Pose2& last, const OdometryIncrement& increment) {
  const Eigen::Matrix2d position = increment.covariance.topLeftCorner<2, 2>();
  if (position.allFinite()) odometry_variance_ += std::max(position.trace(), 0.0);
  odometry_distance_ += increment.motion.Translation().norm();
  const double systematic = options_.odometry_drift * odometry_distance_;
  Motion out;
  geometry::Pose2 motion = increment.motion;
  motion.x *= odometry_scale_;
  motion.y *= odometry_scale_;
  out.predicted = last * motion;
  out.known = true;
  out.odometry = true;
  out.sigma = std::sqrt(odometry_variance_ + systematic * systematic);
  return out;
}

void MotionModel::Fixed() {
  odometry_variance_ = 0.0;
  odometry_distance_ = 0.0;
}

bool MotionModel::CalibrateOdometry(const geometry::Pose2& from, const geometry::Pose2& pose,
                                    const geometry::Pose2& driven) {
  const Eigen::Vector2d read = driven.Translation();
  const double length = read.norm();
  if (!(length >= options_.odometry_scale_span)) return false;
  // Along odometry's own direction: the walls' poses across it are their noise.
  const Eigen::Vector2d walls = (from.Inverse() * pose).Translation();
  scale_ratios_.push_back(walls.dot(read) / (length * length));
  if (scale_ratios_.size() > kSpans) scale_ratios_.pop_front();
  if (scale_ratios_.size() < kMinSpans) return true;
  std::vector<double> sorted(scale_ratios_.begin(), scale_ratios_.end());
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  odometry_scale_ = sorted[sorted.size() / 2];
  return true;
}
}  // namespace relplane::mapper
