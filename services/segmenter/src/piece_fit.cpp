#include "piece_fit.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "relplane/segmenter/dominant_line.hpp"
#include "relplane/segmenter/merge_pieces.hpp"
#include "relplane/segmenter/trimmed_fit.hpp"

namespace relplane::segmenter {
namespace {

// Sets `out`'s plane through `point` with `normal` (unit), turned towards the sensor at the
// origin: the sensor must be on the positive side (d >= 0).
void SetPlaneFacingSensor(const Eigen::Vector3d& normal, const Eigen::Vector3d& point,
                          DetectedPlane* out) {
  const double d = -normal.dot(point);
  out->normal = (d < 0.0 ? -normal : normal).cast<float>();
  out->d = static_cast<float>(std::abs(d));
}

// The least-squares fit of the piece's trimmed moments (about its first fit's centroid).
Piece TrimmedFit(const Piece& p) {
  Piece trimmed;
  trimmed.support = p.support;
  trimmed.stride = p.stride;
  trimmed.count = p.trimmed_count;
  trimmed.sum = p.trimmed_sum;
  trimmed.sum_sq = p.trimmed_sum_sq;
  Refit(p.out.centroid, &trimmed);
  return trimmed;
}

// The rays' share of a fit's scatter, sum d d^T over the points' unit rays d, from their second
// moments about the sensor (at the origin), sum p p^T = scatter + n c c^T, over the mean squared
// range: each point weighs its squared range over the mean, close to one on a short piece, where
// the ray noise tilts the fit. `scatter` about the centroid `c` of `n` points.
Eigen::Matrix3d RaysShare(const Eigen::Matrix3d& scatter, const Eigen::Vector3d& c, double n) {
  const Eigen::Matrix3d second = scatter + n * c * c.transpose();
  const double range2 = second.trace();
  return range2 > 0.0 ? Eigen::Matrix3d((n / range2) * second) : Eigen::Matrix3d::Zero();
}

// Mean over the points (relative to `origin`, in the sensor frame) of (n.d)^2, d the unit ray to
// the point: the share of a ray's noise that lands along the normal, squared.
double MeanSquaredIncidence(const Eigen::Vector3f* points, size_t num_points,
                            const Eigen::Vector3f& origin, const Eigen::Vector3d& normal) {
  if (num_points == 0) return 0.0;
  const Eigen::Vector3f n = normal.cast<float>();
  double sum = 0.0;
  for (size_t i = 0; i < num_points; ++i) {
    const Eigen::Vector3f p = points[i] + origin;
    const float r2 = p.squaredNorm();
    if (r2 > 0.0f) sum += static_cast<double>(n.dot(p) * n.dot(p) / r2);
  }
  return sum / static_cast<double>(num_points);
}

// The lower median (0 when empty): with two pieces, one leaning, the other's.
double LowerMedian(std::vector<double>* values) {
  if (values->empty()) return 0.0;
  const size_t k = (values->size() - 1) / 2;
  std::nth_element(values->begin(), values->begin() + k, values->end());
  return std::max(0.0, (*values)[k]);
}

}  // namespace

// Least-squares refit of a piece from its moments about `origin`; normal towards the sensor.
void Refit(const Eigen::Vector3f& origin, Piece* piece) {
  const double n = piece->count;
  const Eigen::Vector3d mean = piece->sum / n;
  // LocalMoments::AddTo fills the lower triangle only.
  Eigen::Matrix3d sum_sq = piece->sum_sq;
  sum_sq.triangularView<Eigen::StrictlyUpper>() = sum_sq.transpose();
  const Eigen::Matrix3d scatter = sum_sq - n * mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(scatter);
  const Eigen::Vector3d centroid = origin.cast<double>() + mean;
  SetPlaneFacingSensor(eig.eigenvectors().col(0).normalized(), centroid, &piece->out);
  piece->out.centroid = centroid.cast<float>();
  piece->out.num_points = piece->support;
  piece->out.rms = static_cast<float>(std::sqrt(std::max(0.0, eig.eigenvalues()(0)) / n));
  piece->scatter = piece->stride * scatter;  // as if every point had entered the fit
}

// The least-squares fit of the piece's trimmed moments: its scatter, centroid, normal and RMS,
// and the rays' share (RaysShare).
void TrimmedMoments(Piece* p) {
  if (p->trimmed_count < 3) return;
  const Piece trimmed = TrimmedFit(*p);
  p->scatter = trimmed.scatter;  // as if every point had entered the fit
  p->rays = p->stride * RaysShare(trimmed.scatter / p->stride, trimmed.out.centroid.cast<double>(),
                                  p->trimmed_count);
  p->trimmed_centroid = trimmed.out.centroid;
  p->trimmed_normal = trimmed.out.normal.cast<double>();
  p->trimmed_rms = trimmed.out.rms;
}

// Refits the piece to its trimmed moments (TrimmedMoments), the noise along the sensor's rays
// taken out (FitOutRayNoise, at most `max_variance` of it); the extent's axes (u, v) and
// centroid frame stay, the vertices are lifted onto the new plane afterwards.
void TrimmedRefit(double max_variance, Piece* p) {
  if (p->trimmed_count < 3) return;
  const RayNoiseFit fit =
      FitOutRayNoise(p->scatter, p->rays, p->stride * p->trimmed_count, max_variance);
  SetPlaneFacingSensor(fit.normal, p->trimmed_centroid.cast<double>(), &p->out);
  p->out.rms = static_cast<float>(fit.rms);
}

// The noise variance along a ray that grows with range (the camera's, or Options::range_noise),
// at `point`.
double RangeVariance(const Options& options, const Eigen::Vector3d& point) {
  if (options.sensor.Known()) return options.sensor.VarianceAt(static_cast<float>(point.x()));
  const double g = static_cast<double>(options.noise.range_noise) * point.squaredNorm();
  return g * g;
}

// Each kept vertical piece's least-squares fit, refitted over its fitted points within the trim
// of the last fit until they settle (IterateTrimmedFit): what the piece took from a crossing
// face at a convex corner drops out; a piece still leaning between two faces after that is fitted
// to the line most of its points lie on (DominantLineFit). Walls only: the 2½D mapper uses
// nothing else, and a floor holds most of a cloud's points.
void IterateVerticalFits(const Cloud& cloud, const Options& options, PieceWorkspace::Buffers* w,
                         std::vector<Piece>* pieces) {
  // The fitted points (fit_order, grouped by cell) of each vertical piece, in one buffer.
  std::vector<int32_t>& start = w->piece_point_start;
  start.assign(pieces->size() + 1, 0);
  const size_t num_cells = w->cells.size();
  auto vertical_piece = [&](size_t s) {
    const int32_t piece = w->piece_of[s];
    return piece >= 0 && (*pieces)[piece].kept && (*pieces)[piece].vertical &&
                   (*pieces)[piece].trimmed_count >= 3
               ? piece
               : -1;
  };
  for (size_t s = 0; s < num_cells; ++s) {
    const int32_t piece = vertical_piece(s);
    if (piece >= 0) start[piece + 1] += w->fit_start[s + 1] - w->fit_start[s];
  }
  for (size_t k = 0; k < pieces->size(); ++k) start[k + 1] += start[k];
  std::vector<Eigen::Vector3f>& points = w->piece_points;
  points.resize(start.back());
  std::vector<int32_t> next(start.begin(), start.end() - 1);
  for (size_t s = 0; s < num_cells; ++s) {
    const int32_t piece = vertical_piece(s);
    if (piece < 0) continue;
    const Eigen::Vector3f& origin = (*pieces)[piece].trimmed_centroid;
    for (int32_t k = w->fit_start[s]; k < w->fit_start[s + 1]; ++k) {
      const int32_t i = w->fit_order[k];
      points[next[piece]++] = Eigen::Vector3f(cloud.x[i], cloud.y[i], cloud.z[i]) - origin;
    }
  }
  std::vector<PlaneFit> fits(pieces->size());
  std::vector<double> along(pieces->size(), 0.0);  // mean (n.d)^2 over the points' unit rays d
  std::vector<double> ray_variance;                // what each piece's RMS implies along rays
  for (size_t k = 0; k < pieces->size(); ++k) {
    if (start[k + 1] == start[k]) continue;
    const Piece& p = (*pieces)[k];
    PlaneFit fit;
    fit.normal = p.trimmed_normal;
    fit.centroid = p.trimmed_centroid.cast<double>();
    fit.rms = p.trimmed_rms;
    fit.count = p.trimmed_count;
    fits[k] = IterateTrimmedFit(points.data() + start[k], start[k + 1] - start[k],
                                p.trimmed_centroid.cast<double>(), fit, options.extents.trim_sigmas,
                                options.noise.sigma_min, options.extents.max_refits);
    along[k] = MeanSquaredIncidence(points.data() + start[k], start[k + 1] - start[k],
                                    p.trimmed_centroid, fits[k].normal);
    if (fits[k].count >= options.description.min_noise_points && along[k] > 0.0) {
      ray_variance.push_back(fits[k].rms * fits[k].rms / along[k] -
                             RangeVariance(options, fits[k].centroid));
    }
  }
  // The sensor's noise along its rays, from the frame's vertical pieces: the lower median of
  // what each one's RMS implies, so that a leaning piece or two do not raise it. (Described
  // later, the ray-noise fit pools it over all pieces, weighed by their size.)
  const double sensor_variance = LowerMedian(&ray_variance);
  for (size_t k = 0; k < pieces->size(); ++k) {
    if (start[k + 1] == start[k]) continue;
    Piece& p = (*pieces)[k];
    PlaneFit fit = fits[k];
    const double expected =
        std::max(static_cast<double>(options.noise.sigma_min),
                 std::sqrt(std::max(
                     0.0, along[k] * (sensor_variance + RangeVariance(options, fit.centroid)))));
    if (fit.rms > options.description.leaning_rms * expected) {
      const PlaneFit line = DominantLineFit(
          points.data() + start[k], start[k + 1] - start[k], p.trimmed_centroid.cast<double>(), fit,
          options.extents.trim_sigmas * expected, options.extents.trim_sigmas,
          options.noise.sigma_min, options.extents.max_refits, options.description.min_line_share);
      if (line.fits > 0) {
        fit = line;
        p.line_refit = true;
      }
    }
    if (fit.fits == 0) continue;
    p.trimmed_count = fit.count;
    p.trimmed_centroid = fit.centroid.cast<float>();
    p.trimmed_normal = fit.normal;
    p.trimmed_rms = static_cast<float>(fit.rms);
    p.scatter = p.stride * fit.scatter;  // as if every point had entered the fit
    p.rays = p.stride * RaysShare(fit.scatter, fit.centroid, fit.count);
    // TrimmedRefit (Describe) fits the piece to these moments.
  }
}

}  // namespace relplane::segmenter
