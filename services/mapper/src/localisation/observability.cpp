#include "relplane/mapper/observability.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace relplane::mapper {
namespace {

bool Usable(const Eigen::Matrix3d& information) {
  if (!information.allFinite()) return false;
  const double asymmetry = (information - information.transpose()).cwiseAbs().maxCoeff();
  if (asymmetry > 1e-9 * std::max(1.0, information.cwiseAbs().maxCoeff())) return false;
  return information.diagonal().minCoeff() >= 0.0;
}

}  // namespace

Eigen::Matrix3d InformationOf(const std::vector<PoseConstraint>& constraints) {
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  for (const PoseConstraint& c : constraints) {
    if (!c.jacobian.allFinite() || !std::isfinite(c.sigma) || c.sigma <= 0.0) continue;
    information += c.jacobian * c.jacobian.transpose() / (c.sigma * c.sigma);
  }
  return information;
}

Observability AnalyseInformation(const Eigen::Matrix3d& information,
                                 const ObservabilityOptions& options) {
  Observability out;
  out.information = Usable(information) ? information : Eigen::Matrix3d::Zero();
  // Yaw in metres of a point yaw_length away, so one threshold holds for all three axes.
  const Eigen::Vector3d scale(1.0, 1.0, 1.0 / options.yaw_length);
  const Eigen::Matrix3d scaled = scale.asDiagonal() * out.information * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scaled);
  out.eigenvalues = eig.eigenvalues();
  out.eigenvectors = eig.eigenvectors();
  const double min_information =
      1.0 / (options.max_constrained_sigma * options.max_constrained_sigma);
  for (int k = 0; k < 3; ++k) {
    if (out.eigenvalues(k) >= min_information) continue;
    // Back to (x, y, yaw): a scaled direction v is the step (v_x, v_y, v_yaw / length).
    const Eigen::Vector3d v = scale.asDiagonal() * out.eigenvectors.col(k);
    out.unconstrained.push_back(v.normalized());
  }
  const Eigen::Vector3d prior(1.0 / (options.prior_sigma_position * options.prior_sigma_position),
                              1.0 / (options.prior_sigma_position * options.prior_sigma_position),
                              1.0 / (options.prior_sigma_yaw * options.prior_sigma_yaw));
  const Eigen::Matrix3d total = out.information + Eigen::Matrix3d(prior.asDiagonal());
  out.covariance = total.ldlt().solve(Eigen::Matrix3d::Identity());
  out.covariance = 0.5 * (out.covariance + out.covariance.transpose());
  return out;
}

}  // namespace relplane::mapper
