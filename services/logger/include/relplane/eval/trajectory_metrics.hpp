#pragma once
// Trajectory accuracy of the estimate (POSE) against the truth (SIM_TRUTH), matched by seq and
// compared in the x-y plane (2½D: POSE's z is the start pose's z).

#include <cstdint>
#include <limits>
#include <vector>

#include "relplane/common/geometry.hpp"
#include "relplane/eval/types.hpp"

namespace relplane::eval {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct MatchedPose {
  PoseSample estimate;
  PoseSample truth;
};

// Pairs estimate and truth with the same seq, in increasing seq. A repeated seq keeps the last.
std::vector<MatchedPose> MatchBySeq(const std::vector<PoseSample>& estimate,
                                    const std::vector<PoseSample>& truth);

// The rigid 2D motion T minimising sum |T * source_i - target_i|^2 (Umeyama's closed form
// without scale). Identity for fewer than one pair; a pure translation for one pair.
geometry::Pose2 AlignSE2(const std::vector<Eigen::Vector2d>& source,
                         const std::vector<Eigen::Vector2d>& target);

// Error of one matched pose, for error.svg.
struct ErrorSample {
  double t_s = 0.0;         // truth utime in seconds
  double position_m = 0.0;  // |estimate - truth| in x-y, no alignment
  double aligned_m = 0.0;   // the same after SE(2) alignment
  double yaw_deg = 0.0;     // wrapped estimate yaw - truth yaw
  // Signed error along the truth's heading and across it (left), no alignment, and the
  // estimate's standard deviation along each (from POSE's covariance).
  double along_m = 0.0;
  double across_m = 0.0;
  double sigma_along_m = 0.0;
  double sigma_across_m = 0.0;
  int status = 0;  // the estimate's pose status
};

// The share of frames whose error lies within 3 sigma of the covariance the estimate came
// with: the x-y error's Mahalanobis distance (2 dof: 98.9 % of a consistent estimate's frames),
// and the heading error against its own sigma (99.7 %).
struct Consistency {
  int64_t frames = 0;
  double position_within_3sigma = kNaN;
  double yaw_within_3sigma = kNaN;
};

struct TrajectoryMetrics {
  int64_t matched = 0;
  double path_length_m = 0.0;  // of the truth, x-y
  double ate_rmse_m = kNaN;    // no alignment: the first pose anchors the map
  double ate_max_m = kNaN;
  double ate_final_m = kNaN;
  double ate_aligned_rmse_m = kNaN;  // after the best SE(2) alignment
  geometry::Pose2 alignment;         // truth <- estimate
  double yaw_rmse_deg = kNaN;
  double yaw_max_deg = kNaN;
  // Relative pose error over segments of about `rpe_segment_m` of truth path: translation error
  // per metre travelled (RMSE, m/m) and rotation error per metre (RMSE, deg/m).
  double rpe_segment_m = 1.0;
  int64_t rpe_segments = 0;
  double rpe_translation_per_m = kNaN;
  double rpe_rotation_deg_per_m = kNaN;
  Consistency consistency;
  // The same per pose status (index: PoseStatus), frames of that status only.
  Consistency consistency_by_status[5];
  std::vector<ErrorSample> errors;
};

// Whether an error lies within 3 sigma of its covariance (x, y block: Mahalanobis distance;
// a zero covariance holds only an error of zero, to rounding).
bool PositionWithin3Sigma(const Eigen::Vector2d& error, const Eigen::Matrix2d& covariance);
bool YawWithin3Sigma(double error_rad, double variance);

TrajectoryMetrics ComputeTrajectoryMetrics(const std::vector<MatchedPose>& matched,
                                           double rpe_segment_m);

}  // namespace relplane::eval
