#include "relplane/common/covariance.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace relplane::geometry {
namespace {

TEST(Covariance, AcceptsZerosAndAPositiveDefiniteMatrix) {
  std::string reason;
  const double zeros[9] = {};
  EXPECT_TRUE(ValidCovariance(zeros, &reason)) << reason;
  const double c[9] = {1e-4, 2e-5, 0, 2e-5, 4e-4, 1e-6, 0, 1e-6, 1e-5};
  EXPECT_TRUE(ValidCovariance(c, &reason)) << reason;
  double back[9];
  CovarianceToRowMajor(CovarianceFromRowMajor(c), back);
  for (int i = 0; i < 9; ++i) EXPECT_EQ(back[i], c[i]);
  EXPECT_EQ(CovarianceFromRowMajor(c)(0, 1), 2e-5);
  EXPECT_EQ(CovarianceFromRowMajor(c)(2, 1), 1e-6);
}

TEST(Covariance, RejectsNonFiniteAsymmetricAndIndefinite) {
  std::string reason;
  double c[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  c[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(ValidCovariance(c, &reason));
  EXPECT_NE(reason.find("non-finite"), std::string::npos);
  c[4] = 1;
  c[1] = 0.5;  // c[3] stays 0
  EXPECT_FALSE(ValidCovariance(c, &reason));
  EXPECT_NE(reason.find("symmetric"), std::string::npos);
  c[3] = 0.5;
  EXPECT_TRUE(ValidCovariance(c, &reason));
  c[1] = c[3] = 2.0;  // |correlation| > 1: an eigenvalue below zero
  EXPECT_FALSE(ValidCovariance(c, &reason));
  EXPECT_NE(reason.find("semi-definite"), std::string::npos);
  const double negative[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};
  EXPECT_FALSE(ValidCovariance(negative, &reason));
}

}  // namespace
}  // namespace relplane::geometry
