#include "relplane/segmenter/dominant_line.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

namespace relplane::segmenter {
namespace {

// Candidate lines join representative points of these many slices of the piece along its wall,
// three per slice (its points' lower quartile, median and upper quartile across the wall): a
// line through any two of the face's columns is among them. 24 points: 276 lines.
constexpr int kSlices = 8;
// Each candidate is scored on at most this many of the piece's points (every k-th).
constexpr size_t kScorePoints = 1000;
// rad: the line may turn from the start by at most this much, more than a lean towards a
// crossing face gives a piece; a piece whose most points lie on a line turned further holds two
// surfaces, the larger not the one it was fitted to.
constexpr double kMaxTurn = 0.2;
// m: the piece's points must spread at least this far along the wall (5th to 95th percentile)
// for a line through them to be told from their noise: a sliver's is not.
constexpr double kMinSpan = 0.2;

struct Point2 {
  double a = 0.0;  // along the wall
  double b = 0.0;  // across it, along the start's normal
};

}  // namespace

PlaneFit DominantLineFit(const Eigen::Vector3f* points, size_t num_points,
                         const Eigen::Vector3d& origin, const PlaneFit& start, double trim,
                         float trim_sigmas, float sigma_min, int max_fits, double min_share) {
  PlaneFit unchanged = start;
  unchanged.fits = 0;
  if (num_points < 3 * kSlices || !(trim > 0.0)) return unchanged;
  // The frame seen from above: u along the wall, n across it; v is the turning axis.
  const Eigen::Vector3d n = start.normal.normalized();
  Eigen::Vector3d v = Eigen::Vector3d::UnitZ() - n.z() * n;
  if (v.norm() < 0.5) return unchanged;  // not a wall
  v.normalize();
  const Eigen::Vector3d u = v.cross(n);
  const Eigen::Vector3d c = start.centroid - origin;
  std::vector<Point2> flat(num_points);
  for (size_t i = 0; i < num_points; ++i) {
    const Eigen::Vector3d q = points[i].cast<double>() - c;
    flat[i] = {u.dot(q), n.dot(q)};
  }
  // Representative points: slices by `a`, quartiles of `b` within each.
  std::vector<Point2> sorted = flat;
  std::sort(sorted.begin(), sorted.end(),
            [](const Point2& x, const Point2& y) { return x.a < y.a; });
  if (sorted[sorted.size() * 95 / 100].a - sorted[sorted.size() * 5 / 100].a < kMinSpan) {
    return unchanged;
  }
  std::vector<Point2> reps;
  for (int s = 0; s < kSlices; ++s) {
    const size_t lo = sorted.size() * s / kSlices, hi = sorted.size() * (s + 1) / kSlices;
    std::vector<Point2> slice(sorted.begin() + lo, sorted.begin() + hi);
    for (const double share : {0.25, 0.5, 0.75}) {
      const size_t k = std::min(slice.size() - 1, static_cast<size_t>(share * slice.size()));
      std::nth_element(slice.begin(), slice.begin() + k, slice.end(),
                       [](const Point2& x, const Point2& y) { return x.b < y.b; });
      reps.push_back(slice[k]);
    }
  }
  const size_t step = std::max<size_t>(1, num_points / kScorePoints);
  int best = -1;
  Eigen::Vector2d best_normal(0.0, 1.0);
  double best_offset = 0.0;
  for (size_t i = 0; i < reps.size(); ++i) {
    for (size_t j = i + 1; j < reps.size(); ++j) {
      const Eigen::Vector2d d(reps[j].a - reps[i].a, reps[j].b - reps[i].b);
      if (d.norm() < 1e-6 || std::abs(d.y()) > std::tan(kMaxTurn) * std::abs(d.x())) continue;
      const Eigen::Vector2d m = Eigen::Vector2d(-d.y(), d.x()).normalized();
      const double offset = m.x() * reps[i].a + m.y() * reps[i].b;
      int count = 0;
      for (size_t k = 0; k < num_points; k += step) {
        if (std::abs(m.x() * flat[k].a + m.y() * flat[k].b - offset) <= trim) ++count;
      }
      if (count > best) best = count, best_normal = m, best_offset = offset;
    }
  }
  if (best < 0) return unchanged;
  // The best line's points within the trim, fitted by least squares: the start for the refits.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
  int count = 0;
  for (size_t k = 0; k < num_points; ++k) {
    if (std::abs(best_normal.x() * flat[k].a + best_normal.y() * flat[k].b - best_offset) > trim) {
      continue;
    }
    const Eigen::Vector3d q = points[k].cast<double>() - c;
    sum += q;
    sum_sq.noalias() += q * q.transpose();
    ++count;
  }
  if (count < 3) return unchanged;
  const Eigen::Vector3d mean = sum / count;
  const Eigen::Matrix3d scatter = sum_sq - count * mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(scatter);
  PlaneFit fit;
  fit.normal = eig.eigenvectors().col(0).normalized();
  if (fit.normal.dot(start.normal) < 0.0) fit.normal = -fit.normal;
  fit.centroid = start.centroid + mean;
  fit.rms = std::sqrt(std::max(0.0, eig.eigenvalues()(0)) / count);
  fit.scatter = scatter;
  fit.count = count;
  PlaneFit refit =
      IterateTrimmedFit(points, num_points, origin, fit, trim_sigmas, sigma_min, max_fits, trim);
  if (refit.fits == 0) refit = fit;
  refit.fits += 1;
  if (refit.count < min_share * start.count ||
      refit.normal.dot(start.normal) < std::cos(kMaxTurn)) {
    return unchanged;
  }
  return refit;
}

}  // namespace relplane::segmenter
