#pragma once
// A piece of an EM plane (its points in one connected region of the grid) and the least-squares
// fits that describe it: refit from its moments, trimmed to the points near the first fit, the
// noise along the sensor's rays taken out. Private to the segmenter library (extent.cpp).

#include <Eigen/Core>

#include "piece_grid.hpp"
#include "relplane/segmenter/extent.hpp"
#include "relplane/segmenter/wall_ends.hpp"

namespace relplane::segmenter {

struct Piece {
  int plane = 0;    // the EM plane it came from
  int support = 0;  // all its points
  int count = 0;    // the points that enter the fit (sum, sum_sq): one in `stride`
  double stride = 1.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
  bool kept = false;
  bool vertical = false;
  DetectedPlane out;
  Eigen::Matrix3d scatter;  // about the centroid
  // Second pass: moments of the points close to the first fit, about its centroid.
  int trimmed_count = 0;
  Eigen::Vector3f trimmed_centroid = Eigen::Vector3f::Constant(kInf);
  Eigen::Vector3d trimmed_sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d trimmed_sum_sq = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d rays = Eigen::Matrix3d::Zero();  // sum of d d^T over the fitted points' rays d
  Eigen::Vector3d trimmed_normal = Eigen::Vector3d::Zero();  // least squares
  float trimmed_rms = 0.0f;
  float trim = 0.0f;  // distance from the first fit within which points are kept
  // How far the distance to the first fit varies over a cell of its grid: along the grid's
  // axes (half a cell each way), and per unit of distance from the EM plane.
  float cell_spread = 0.0f, normal_spread = 0.0f;
  Eigen::Vector3f u, v;
  float a_min = kInf, a_max = -kInf, b_min = kInf, b_max = -kInf;
  EndBuffer lo_end, hi_end;  // a vertical piece's points furthest out along u each way
  bool line_refit = false;   // its fit was the line most of its points lie on (DominantLineFit)
};

// Least-squares refit of a piece from its moments about `origin`; normal towards the sensor.
void Refit(const Eigen::Vector3f& origin, Piece* piece);

// The least-squares fit of the piece's trimmed moments: its scatter, centroid, normal and RMS,
// and the rays' share (RaysShare).
void TrimmedMoments(Piece* p);

// Refits the piece to its trimmed moments (TrimmedMoments), the noise along the sensor's rays
// taken out (FitOutRayNoise, at most `max_variance` of it); the extent's axes (u, v) and
// centroid frame stay, the vertices are lifted onto the new plane afterwards.
void TrimmedRefit(double max_variance, Piece* p);

// The noise variance along a ray that grows with range (the camera's, or Options::range_noise),
// at `point`.
double RangeVariance(const Options& options, const Eigen::Vector3d& point);

// Each kept vertical piece's least-squares fit, refitted over its fitted points within the trim
// of the last fit until they settle (IterateTrimmedFit): what the piece took from a crossing
// face at a convex corner drops out; a piece still leaning between two faces after that is fitted
// to the line most of its points lie on (DominantLineFit). Walls only: the 2½D mapper uses
// nothing else, and a floor holds most of a cloud's points.
void IterateVerticalFits(const Cloud& cloud, const Options& options, PieceWorkspace::Buffers* w,
                         std::vector<Piece>* pieces);

}  // namespace relplane::segmenter
