#include "relplane/segmenter/trimmed_fit.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace relplane::segmenter {
namespace {

// The fit has settled when the points within the trim change by at most one in this many.
constexpr int kSettled = 500;

// The RMS of a unit Gaussian cut at +-k, over sigma (k = 2.5: 0.955).
double CutGaussianRmsShare(double k) {
  const double density = std::exp(-0.5 * k * k) / std::sqrt(2.0 * M_PI);
  const double mass = std::erf(k / std::sqrt(2.0));
  return std::sqrt(std::max(1e-6, 1.0 - 2.0 * k * density / mass));
}

}  // namespace

PlaneFit IterateTrimmedFit(const Eigen::Vector3f* points, size_t num_points,
                           const Eigen::Vector3d& origin, const PlaneFit& start, float trim_sigmas,
                           float sigma_min, int max_fits, double max_trim) {
  PlaneFit fit = start;
  fit.fits = 0;
  const double share = CutGaussianRmsShare(trim_sigmas);
  double sigma = start.rms / share;
  for (int k = 0; k < max_fits; ++k) {
    const double trim =
        std::min(max_trim, trim_sigmas * std::max(sigma, static_cast<double>(sigma_min)));
    // About the current centroid, in float: the points lie within the piece's extent of it.
    const Eigen::Vector3f n = fit.normal.cast<float>();
    const Eigen::Vector3f c = (fit.centroid - origin).cast<float>();
    const float offset = n.dot(c);
    const float t = static_cast<float>(trim);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
    int count = 0;
    for (size_t i = 0; i < num_points; ++i) {
      const Eigen::Vector3f& p = points[i];
      if (std::fabs(n.dot(p) - offset) > t) continue;
      const Eigen::Vector3d q = (p - c).cast<double>();
      sum += q;
      sum_sq.noalias() += q * q.transpose();
      ++count;
    }
    // Settled: (nearly) the same points give (nearly) the same fit. On a clean plane a point or
    // two at the trim's edge goes in and out from fit to fit.
    if (count < 3 || std::abs(count - fit.count) * kSettled <= count) break;
    const Eigen::Vector3d mean = sum / count;
    const Eigen::Matrix3d scatter = sum_sq - count * mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(scatter);
    Eigen::Vector3d normal = eig.eigenvectors().col(0).normalized();
    if (normal.dot(fit.normal) < 0.0) normal = -normal;
    fit.normal = normal;
    fit.centroid += mean;
    fit.rms = std::sqrt(std::max(0.0, eig.eigenvalues()(0)) / count);
    fit.scatter = scatter;
    fit.count = count;
    ++fit.fits;
    sigma = fit.rms / share;
  }
  return fit;
}

}  // namespace relplane::segmenter
