#include "eigen_solver_2d.hpp"

template Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>&
Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>::compute(const Eigen::EigenBase<Eigen::Matrix2d>&,
                                                         int);
