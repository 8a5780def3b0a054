#include "relplane/eval/trajectory_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace relplane::eval {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

geometry::Pose2 PlanarPose(const PoseSample& p) {
  return {p.position.x(), p.position.y(), geometry::YawOf(p.orientation)};
}

double Rms(double sum_squares, int64_t n) { return n > 0 ? std::sqrt(sum_squares / n) : kNaN; }

// Rounding left in a covariance, and a floor under it so a zero covariance is invertible.
constexpr double kVarianceFloor = 1e-12;  // m^2 or rad^2

struct ConsistencyCount {
  int64_t frames = 0, position = 0, yaw = 0;
  Consistency Share() const {
    Consistency c;
    c.frames = frames;
    if (frames > 0) {
      c.position_within_3sigma = static_cast<double>(position) / static_cast<double>(frames);
      c.yaw_within_3sigma = static_cast<double>(yaw) / static_cast<double>(frames);
    }
    return c;
  }
};

// Relative pose error (Sturm et al.'s RPE, by distance travelled instead of time) over segments
// of at least `segment_m` of truth path, normalised per metre.
void ComputeRpe(const std::vector<MatchedPose>& matched, const std::vector<double>& path,
                TrajectoryMetrics* m) {
  double sum_t = 0.0;
  double sum_r = 0.0;
  size_t j = 0;
  for (size_t i = 0; i < matched.size(); ++i) {
    j = std::max(j, i + 1);
    while (j < matched.size() && path[j] - path[i] < m->rpe_segment_m) ++j;
    if (j >= matched.size()) break;
    const double length = path[j] - path[i];
    const geometry::Pose2 rel_truth =
        PlanarPose(matched[i].truth).Inverse() * PlanarPose(matched[j].truth);
    const geometry::Pose2 rel_est =
        PlanarPose(matched[i].estimate).Inverse() * PlanarPose(matched[j].estimate);
    const double dt = (rel_truth.Translation() - rel_est.Translation()).norm() / length;
    const double dr =
        std::abs(geometry::WrapAngle(rel_truth.yaw - rel_est.yaw)) * kRadToDeg / length;
    sum_t += dt * dt;
    sum_r += dr * dr;
    ++m->rpe_segments;
  }
  m->rpe_translation_per_m = Rms(sum_t, m->rpe_segments);
  m->rpe_rotation_deg_per_m = Rms(sum_r, m->rpe_segments);
}

}  // namespace

bool PositionWithin3Sigma(const Eigen::Vector2d& error, const Eigen::Matrix2d& covariance) {
  const Eigen::Matrix2d c = covariance + kVarianceFloor * Eigen::Matrix2d::Identity();
  return error.dot(c.ldlt().solve(error)) <= 9.0;
}

bool YawWithin3Sigma(double error_rad, double variance) {
  return error_rad * error_rad <= 9.0 * (std::max(variance, 0.0) + kVarianceFloor);
}

std::vector<MatchedPose> MatchBySeq(const std::vector<PoseSample>& estimate,
                                    const std::vector<PoseSample>& truth) {
  std::map<int64_t, const PoseSample*> truth_by_seq;
  for (const PoseSample& t : truth) truth_by_seq[t.seq] = &t;
  std::map<int64_t, MatchedPose> by_seq;
  for (const PoseSample& e : estimate) {
    const auto it = truth_by_seq.find(e.seq);
    if (it != truth_by_seq.end()) by_seq[e.seq] = {e, *it->second};
  }
  std::vector<MatchedPose> out;
  out.reserve(by_seq.size());
  for (const auto& [seq, pair] : by_seq) out.push_back(pair);
  return out;
}

geometry::Pose2 AlignSE2(const std::vector<Eigen::Vector2d>& source,
                         const std::vector<Eigen::Vector2d>& target) {
  const size_t n = std::min(source.size(), target.size());
  if (n == 0) return {};
  Eigen::Vector2d mean_s = Eigen::Vector2d::Zero();
  Eigen::Vector2d mean_t = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < n; ++i) {
    mean_s += source[i];
    mean_t += target[i];
  }
  mean_s /= static_cast<double>(n);
  mean_t /= static_cast<double>(n);
  // In 2D the SVD of Umeyama's cross-covariance reduces to one angle: the rotation that best
  // turns the centred source onto the centred target.
  double sin_sum = 0.0;
  double cos_sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d s = source[i] - mean_s;
    const Eigen::Vector2d t = target[i] - mean_t;
    cos_sum += s.dot(t);
    sin_sum += s.x() * t.y() - s.y() * t.x();
  }
  const double yaw = (sin_sum == 0.0 && cos_sum == 0.0) ? 0.0 : std::atan2(sin_sum, cos_sum);
  const Eigen::Vector2d translation = mean_t - Eigen::Rotation2Dd(yaw) * mean_s;
  return {translation.x(), translation.y(), yaw};
}

TrajectoryMetrics ComputeTrajectoryMetrics(const std::vector<MatchedPose>& matched,
                                           double rpe_segment_m) {
  TrajectoryMetrics m;
  m.rpe_segment_m = rpe_segment_m;
  m.matched = static_cast<int64_t>(matched.size());
  if (matched.empty()) return m;

  std::vector<Eigen::Vector2d> est;
  std::vector<Eigen::Vector2d> truth;
  std::vector<double> path(matched.size(), 0.0);
  for (size_t i = 0; i < matched.size(); ++i) {
    est.push_back(matched[i].estimate.position.head<2>());
    truth.push_back(matched[i].truth.position.head<2>());
    if (i > 0) path[i] = path[i - 1] + (truth[i] - truth[i - 1]).norm();
  }
  m.path_length_m = path.back();
  m.alignment = AlignSE2(est, truth);

  double sum_raw = 0.0;
  double sum_aligned = 0.0;
  double sum_yaw = 0.0;
  ConsistencyCount all;
  ConsistencyCount by_status[5];
  m.ate_max_m = 0.0;
  m.yaw_max_deg = 0.0;
  for (size_t i = 0; i < matched.size(); ++i) {
    ErrorSample e;
    e.t_s = static_cast<double>(matched[i].truth.utime) * 1e-6;
    e.position_m = (est[i] - truth[i]).norm();
    e.aligned_m = (m.alignment * est[i] - truth[i]).norm();
    e.yaw_deg = geometry::WrapAngle(geometry::YawOf(matched[i].estimate.orientation) -
                                    geometry::YawOf(matched[i].truth.orientation)) *
                kRadToDeg;
    const PoseSample& estimate = matched[i].estimate;
    const Eigen::Vector2d error = est[i] - truth[i];
    const Eigen::Vector2d heading =
        Eigen::Rotation2Dd(geometry::YawOf(matched[i].truth.orientation)) *
        Eigen::Vector2d::UnitX();
    const Eigen::Vector2d left(-heading.y(), heading.x());
    const Eigen::Matrix2d cov_xy = estimate.covariance.topLeftCorner<2, 2>();
    e.along_m = error.dot(heading);
    e.across_m = error.dot(left);
    e.sigma_along_m = std::sqrt(std::max(heading.dot(cov_xy * heading), 0.0));
    e.sigma_across_m = std::sqrt(std::max(left.dot(cov_xy * left), 0.0));
    e.status = estimate.status;
    const bool position_ok = PositionWithin3Sigma(error, cov_xy);
    const bool yaw_ok = YawWithin3Sigma(e.yaw_deg / kRadToDeg, estimate.covariance(2, 2));
    for (ConsistencyCount* c :
         {&all,
          estimate.status >= 0 && estimate.status < 5 ? &by_status[estimate.status] : nullptr}) {
      if (c == nullptr) continue;
      ++c->frames;
      c->position += position_ok ? 1 : 0;
      c->yaw += yaw_ok ? 1 : 0;
    }
    sum_raw += e.position_m * e.position_m;
    sum_aligned += e.aligned_m * e.aligned_m;
    sum_yaw += e.yaw_deg * e.yaw_deg;
    m.ate_max_m = std::max(m.ate_max_m, e.position_m);
    m.yaw_max_deg = std::max(m.yaw_max_deg, std::abs(e.yaw_deg));
    m.errors.push_back(e);
  }
  m.ate_rmse_m = Rms(sum_raw, m.matched);
  m.ate_aligned_rmse_m = Rms(sum_aligned, m.matched);
  m.ate_final_m = m.errors.back().position_m;
  m.yaw_rmse_deg = Rms(sum_yaw, m.matched);
  m.consistency = all.Share();
  for (int s = 0; s < 5; ++s) m.consistency_by_status[s] = by_status[s].Share();
  ComputeRpe(matched, path, &m);
  return m;
}

}  // namespace relplane::eval
