#pragma once
// The mapper's 2x2 symmetric eigen-decompositions (open directions of positions and groups)
// share one compiled Eigen::SelfAdjointEigenSolver<Matrix2d>::compute, in eigen_solver_2d.cpp:
// instantiated in a source it is about 5 s of -O3, the 3x3 one well under a second. Include this
// header instead of <Eigen/Eigenvalues> wherever a Matrix2d is decomposed.

#include <Eigen/Eigenvalues>

extern template Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>&
Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>::compute(const Eigen::EigenBase<Eigen::Matrix2d>&,
                                                         int);
