#include "relplane/segmenter/proposals.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace relplane::segmenter {
namespace {

constexpr size_t kMaxScoringPoints = 600;
struct Fit {
  EmPlane plane;
  float rms = 0.0f;
  bool ok = false;
};

Fit FitIndices(const Cloud& pts, const std::vector<int>& idx, double max_flatness) {
  Fit fit;
  if (idx.size() < 3) return fit;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i : idx) mean += pts.Point(i).cast<double>();
  mean /= static_cast<double>(idx.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (int i : idx) {
    const Eigen::Vector3d q = pts.Point(i).cast<double>() - mean;
    scatter.noalias() += q * q.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(scatter);
  // A line-like neighbourhood has no defined normal; a thick one (across an edge) is no plane.
  if (eig.eigenvalues()(1) < 1e-6 * static_cast<double>(idx.size())) return fit;
  if (eig.eigenvalues()(0) > max_flatness * eig.eigenvalues()(1)) return fit;
  const Eigen::Vector3d n = eig.eigenvectors().col(0).normalized();
  fit.plane.normal = n.cast<float>();
  fit.plane.d = static_cast<float>(-n.dot(mean));
  fit.plane.centroid = mean.cast<float>();
  fit.rms = static_cast<float>(std::sqrt(std::max(0.0, eig.eigenvalues()(0)) / idx.size()));
  fit.ok = true;
  return fit;
}

std::vector<int> Inliers(const Cloud& pts, const std::vector<int>& idx, const EmPlane& plane,
                         float threshold) {
  std::vector<int> inliers;
  for (const int i : idx) {
    const float dist = plane.normal.dot(pts.Point(i)) + plane.d;
    if (std::fabs(dist) < threshold) inliers.push_back(i);
  }
  return inliers;
}

// How many of every stride-th index are inliers (a trial's score: counted, not collected).
size_t CountInliers(const Cloud& pts, const std::vector<int>& idx, const EmPlane& plane,
                    float threshold, size_t stride) {
  size_t count = 0;
  for (size_t k = 0; k < idx.size(); k += stride) {
    const float dist = plane.normal.dot(pts.Point(idx[k])) + plane.d;
    count += std::fabs(dist) < threshold;
  }
  return count;
}

// One proposal: the best flat neighbourhood's plane, refitted to its inliers.
bool ProposeOne(const Cloud& pts, const std::vector<int>& candidates, const Options& options,
                int min_support, std::mt19937* rng, EmPlane* out, std::vector<int>* support) {
  const float radius2 = options.proposals.radius * options.proposals.radius;
  const size_t stride = std::max<size_t>(1, candidates.size() / kMaxScoringPoints);
  Fit best;
  size_t best_score = 0;
  std::vector<std::pair<float, int>> near;
  std::vector<int> neighbours;
  // The candidates' coordinates side by side, so each trial's distances are one vectorised loop.
  const size_t m = candidates.size();
  std::vector<float> cx(m), cy(m), cz(m), d2(m);
  near.resize(m);
  for (size_t k = 0; k < m; ++k) {
    cx[k] = pts.x[candidates[k]];
    cy[k] = pts.y[candidates[k]];
    cz[k] = pts.z[candidates[k]];
  }
  for (int trial = 0; trial < options.proposals.trials; ++trial) {
    // The seed's nearest candidates (within proposals.radius): a neighbourhood that adapts to
    // the sampling density, so small faces close to the sensor still fit in one.
    const size_t seed = (*rng)() % m;
    const float sx = cx[seed], sy = cy[seed], sz = cz[seed];
    for (size_t k = 0; k < m; ++k) {
      const float dx = cx[k] - sx, dy = cy[k] - sy, dz = cz[k] - sz;
      d2[k] = dx * dx + dy * dy + dz * dz;
    }
    // Every candidate is written and the count advances past those within the radius: no
    // branch to mispredict.
    size_t within = 0;
    for (size_t k = 0; k < m; ++k) {
      near[within] = {d2[k], candidates[k]};
      within += d2[k] < radius2;
    }
    if (static_cast<int>(within) < options.proposals.min_neighbours) continue;
    const size_t keep = std::min(within, static_cast<size_t>(options.proposals.neighbours));
    std::nth_element(near.begin(), near.begin() + (keep - 1), near.begin() + within);
    neighbours.resize(keep);
    for (size_t m = 0; m < keep; ++m) neighbours[m] = near[m].second;
    Fit fit = FitIndices(pts, neighbours, options.proposals.max_flatness);
    // With a known camera a neighbourhood is flat when within twice what the camera resolves
    // at the seed's depth: at range its noise alone exceeds proposal_max_rms.
    const float max_rms =
        options.sensor.Known()
            ? std::max(options.proposals.max_rms, 2.0f * std::sqrt(options.sensor.VarianceAt(sx)))
            : options.proposals.max_rms;
    if (!fit.ok || fit.rms > max_rms) continue;
    const float sigma = std::clamp(fit.rms, options.noise.sigma_min, options.noise.sigma_max);
    const size_t score =
        CountInliers(pts, candidates, fit.plane, options.proposals.inlier_sigmas * sigma, stride);
    if (score > best_score) {
      best_score = score;
      best = fit;
      best.plane.sigma = sigma;
    }
  }
  if (!best.ok) return false;
  // Two refits on all inliers pull the local estimate onto the whole planar support.
  EmPlane plane = best.plane;
  std::vector<int> inliers;
  for (int pass = 0; pass < 2; ++pass) {
    inliers = Inliers(pts, candidates, plane, options.proposals.inlier_sigmas * plane.sigma);
    const Fit refit = FitIndices(pts, inliers, options.proposals.max_flatness);
    if (!refit.ok) return false;
    plane.normal = refit.plane.normal;
    plane.d = refit.plane.d;
    plane.centroid = refit.plane.centroid;
    plane.sigma = std::clamp(std::max(refit.rms, options.noise.sigma_initial * 0.5f),
                             options.noise.sigma_min, options.noise.sigma_max);
  }
  inliers = Inliers(pts, candidates, plane, options.proposals.inlier_sigmas * plane.sigma);
  if (static_cast<int>(inliers.size()) < min_support) return false;
  plane.support = static_cast<float>(inliers.size());
  *out = plane;
  *support = std::move(inliers);
  return true;
}

}  // namespace

std::vector<EmPlane> ProposePlanes(const Cloud& points, std::vector<int> candidates,
                                   const Options& options, int min_support, std::mt19937* rng) {
  std::vector<EmPlane> proposals;
  while (static_cast<int>(proposals.size()) < options.proposals.max_per_round &&
         static_cast<int>(candidates.size()) >= min_support) {
    EmPlane plane;
    std::vector<int> support;
    if (!ProposeOne(points, candidates, options, min_support, rng, &plane, &support)) break;
    proposals.push_back(plane);
    // Both lists are in ascending index order: remove the support from the candidates.
    std::vector<int> rest;
    std::set_difference(candidates.begin(), candidates.end(), support.begin(), support.end(),
                        std::back_inserter(rest));
    candidates.swap(rest);
  }
  return proposals;
}

}  // namespace relplane::segmenter
