#include "relplane/common/covariance.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace relplane::geometry {

Eigen::Matrix3d CovarianceFromRowMajor(const double row_major[9]) {
  Eigen::Matrix3d c;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) c(r, k) = row_major[3 * r + k];
  }
  return c;
}

void CovarianceToRowMajor(const Eigen::Matrix3d& covariance, double row_major[9]) {
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) row_major[3 * r + k] = covariance(r, k);
  }
}

bool ValidCovariance(const double row_major[9], std::string* reason) {
  const Eigen::Matrix3d c = CovarianceFromRowMajor(row_major);
  if (!c.allFinite()) {
    *reason = "covariance has a non-finite number";
    return false;
  }
  // Relative tolerances: a covariance computed in doubles is symmetric and PSD to rounding.
  const double scale = std::max(c.cwiseAbs().maxCoeff(), 1e-300);
  if ((c - c.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    *reason = "covariance is not symmetric";
    return false;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(c, Eigen::EigenvaluesOnly);
  if (eig.eigenvalues()(0) < -1e-9 * scale) {
    *reason = "covariance is not positive semi-definite";
    return false;
  }
  return true;
}

}  // namespace relplane::geometry
