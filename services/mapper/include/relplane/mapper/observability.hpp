#pragma once
// Observability of one frame's pose: how much the constraints a localisation solve used fix
// (x, y, yaw), which directions they leave open, and the covariance the pose is published with.
// The directions come from the eigen-decomposition of the solve's information matrix (Zhang,
// Kaess, Singh, "On degeneracy of optimization-based state estimation problems", ICRA 2016):
// an eigenvector whose eigenvalue is small is a direction the measurements do not fix.

#include <Eigen/Core>
#include <vector>

namespace relplane::mapper {

// One scalar constraint of a solve: its residual changes by jacobian . (dx, dy, dyaw), and it
// is good to `sigma` (m for a wall's line or end, rad for a heading).
struct PoseConstraint {
  Eigen::Vector3d jacobian = Eigen::Vector3d::Zero();
  double sigma = 1.0;
};

struct ObservabilityOptions {
  // The prior every frame's pose has before its constraints: the covariance along a direction
  // nothing constrains. A room's size and a quarter turn; what no plane fixes is that unknown.
  double prior_sigma_position = 1.0;  // m
  double prior_sigma_yaw = 0.5;       // rad
  // A direction is constrained when the constraints alone fix it to this (1 sigma). Yaw is
  // compared through yaw_length: a heading error of e rad moves a point yaw_length away by
  // e * yaw_length m. Two walls 11 degrees apart, each good to 1 cm, fix the direction across
  // their bisector to about 7 cm: still constrained; a single wall's direction along it is not.
  double max_constrained_sigma = 0.1;  // m
  double yaw_length = 1.0;             // m per rad
};

struct Observability {
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();  // sum of J^T J / sigma^2
  // Eigen-decomposition of the information with yaw scaled by yaw_length (so all three axes
  // are in m^-2): eigenvalues ascending, unit eigenvectors as columns in (x, y, yaw * length).
  Eigen::Vector3d eigenvalues = Eigen::Vector3d::Zero();
  Eigen::Matrix3d eigenvectors = Eigen::Matrix3d::Identity();
  // The eigenvectors whose eigenvalue is below 1 / max_constrained_sigma^2, in (x, y, yaw)
  // (yaw unscaled), unit length.
  std::vector<Eigen::Vector3d> unconstrained;
  // (information + prior information)^-1: near the constraints' own covariance where they fix
  // the pose, near the prior along a direction they leave open. Row-major (x, y, yaw).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();

  bool FullyConstrained() const { return unconstrained.empty(); }
};

// The information matrix of the constraints: sum of J^T J / sigma^2. A constraint with a
// non-finite or non-positive sigma, or a non-finite Jacobian, adds nothing.
Eigen::Matrix3d InformationOf(const std::vector<PoseConstraint>& constraints);

// Eigen-decomposition, open directions and covariance of an information matrix (symmetric,
// positive semi-definite; anything else is treated as no information).
Observability AnalyseInformation(const Eigen::Matrix3d& information,
                                 const ObservabilityOptions& options = {});

inline Observability AnalyseObservability(const std::vector<PoseConstraint>& constraints,
                                          const ObservabilityOptions& options = {}) {
  return AnalyseInformation(InformationOf(constraints), options);
}

}  // namespace relplane::mapper
