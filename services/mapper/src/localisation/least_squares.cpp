#include "localisation/least_squares.hpp"

#include "eigen_solver_2d.hpp"

namespace relplane::mapper {

Eigen::Vector2d SolveWithPrior(const Eigen::Matrix2d& a, const Eigen::Vector2d& b,
                               const Eigen::Vector2d& previous, double prior_weight,
                               double min_information, double open_information) {
  // Solved along the eigenvectors of a, so the open direction is decoupled from the others.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(a);
  const double prior = eig.eigenvalues()(0) < min_information ? prior_weight : 0.0;
  Eigen::Vector2d pos = Eigen::Vector2d::Zero();
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d v = eig.eigenvectors().col(k);
    const double lambda = eig.eigenvalues()(k);
    pos +=
        v * (lambda < open_information ? v.dot(previous)
                                       : (v.dot(b) + prior * v.dot(previous)) / (lambda + prior));
  }
  return pos;
}

}  // namespace relplane::mapper
