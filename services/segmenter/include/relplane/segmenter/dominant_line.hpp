#pragma once
// A vertical piece's plane from the one line, seen from above, that most of its points lie on:
// for a grazing face whose piece took a few columns of samples from the face it meets at a
// convex corner.

#include <Eigen/Core>
#include <cstddef>

#include "relplane/segmenter/trimmed_fit.hpp"

namespace relplane::segmenter {

// Why: a pilaster's 0.4 m front, seen at a grazing angle, is three or four of the sensor's
// columns of samples; EM gives its piece one or two columns of the square-on side next to the
// corner as well, 2-5 cm behind it. The least-squares fit leans between the two (several
// degrees at 1 cm noise, enough for the mapper to take the face for a second wall), its RMS
// grows to several times the noise expected along it, and a trim at that RMS
// (IterateTrimmedFit) keeps them all. Trimming down from there drops the face's own samples at
// the corner as readily as the side's, but seen from above the face's samples lie on one line
// and the side's do not.
//
// Tries lines through pairs of points, turning about the piece's vertical axis (the in-plane
// direction nearest +z), and keeps the one with the most points within `trim` of it; its points
// within the trim are fitted and refitted as IterateTrimmedFit does (`trim_sigmas`, `sigma_min`,
// `max_fits`), never with a wider trim than `trim`.
// Returns `start` (fits = 0) unless that fit keeps at least `min_share` of start.count points
// and turns from it by at most 0.2 rad (a piece mostly of another surface is left alone), and
// for a piece whose points spread less than 0.2 m along the wall (no line to tell from noise).
// `points` are relative to `origin`; `start` is the piece's fit so far. Deterministic.
PlaneFit DominantLineFit(const Eigen::Vector3f* points, size_t num_points,
                         const Eigen::Vector3d& origin, const PlaneFit& start, double trim,
                         float trim_sigmas, float sigma_min, int max_fits, double min_share);

}  // namespace relplane::segmenter
