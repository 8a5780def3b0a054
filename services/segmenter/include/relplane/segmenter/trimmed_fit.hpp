#pragma once
// A piece's plane refitted by least squares over its points near the fit, repeated until the
// set of those points settles: the points a piece took from a crossing face drop out.

#include <Eigen/Core>
#include <cstddef>
#include <limits>

namespace relplane::segmenter {

struct PlaneFit {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // unit; its sign follows `start`'s
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // of the points within the trim
  double rms = 0.0;                                    // their distance to the plane
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();   // about their centroid
  int count = 0;                                       // the points within the trim
  int fits = 0;  // least-squares fits made: 0 when the start stood
};

// Points within `trim_sigmas` noise sigmas of the plane are fitted by least squares, and again
// with the new fit's points, at most `max_fits` times, until the number within changes by at
// most one in 500 (then, and with fewer than 3 points, the last fit stands).
// The sigma is the fit's RMS over the points kept, scaled up by what cutting a Gaussian at
// +-trim_sigmas takes off it (2.5 sigmas: 4.5 %), so that on a clean plane the trim stays put;
// it is at least `sigma_min`. `start` is the least-squares fit of `start.count` of the points,
// those within a trim of an earlier fit. `points` (num_points of them) are relative to `origin`,
// all within a piece's extent of it, so float keeps sub-millimetre precision.
//
// Why: at a convex corner (a pilaster's front seen at a grazing angle, its side square on) EM
// gives the grazing face's mixture plane the side's points near the corner, and a plane within
// a few centimetres of them. Its piece's first fit leans towards them by up to several degrees
// and its RMS grows with them, so one trim at 2.5 of that RMS keeps most of them; each refit
// leans less and trims tighter.
// `max_trim` (m) caps the trim: a fit that starts on one surface of several cannot grow back
// over the others (DominantLineFit).
PlaneFit IterateTrimmedFit(const Eigen::Vector3f* points, size_t num_points,
                           const Eigen::Vector3d& origin, const PlaneFit& start, float trim_sigmas,
                           float sigma_min, int max_fits,
                           double max_trim = std::numeric_limits<double>::infinity());

}  // namespace relplane::segmenter
