#pragma once
// Fits the segmenter's plane-fit tests start from and judge by, for faces whose true normal is
// -y (towards a sensor on the -y side).

#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

#include "relplane/segmenter/trimmed_fit.hpp"

namespace relplane::segmenter::testing {

// The plain least-squares fit of every point, as a piece's first fit is; its normal towards -y.
inline PlaneFit LeastSquares(const std::vector<Eigen::Vector3f>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p.cast<double>();
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector3d q = p.cast<double>() - mean;
    scatter += q * q.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  PlaneFit fit;
  fit.normal = eig.eigenvectors().col(0);
  if (fit.normal.y() > 0.0) fit.normal = -fit.normal;
  fit.centroid = mean;
  fit.rms = std::sqrt(eig.eigenvalues()(0) / points.size());
  fit.scatter = scatter;
  fit.count = static_cast<int>(points.size());
  return fit;
}

// Angle between a fit's normal and the true normal -y, degrees.
inline double ErrorDeg(const PlaneFit& fit) {
  const Eigen::Vector3d truth(0, -1, 0);
  return std::atan2(truth.cross(fit.normal).norm(), truth.dot(fit.normal)) * 180.0 / M_PI;
}

}  // namespace relplane::segmenter::testing
