#pragma once
// The EM core: a mixture of planes plus an outlier class (Thrun et al., "Using EM to learn 3D
// models of indoor environments", the segmenter of the paper's §III input stage).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter {

// One mixture component: an infinite plane normal . p + d = 0 with Gaussian noise sigma along
// the normal.
struct EmPlane {
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();
  float d = 0.0f;
  float sigma = 0.01f;
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  // weighted mean of its support
  float support = 0.0f;                                // sum of responsibilities
};

// Responsibilities of K planes and the outlier class for n points, plane-major:
// r[j * n + i] for plane j < K, r[K * n + i] for the outlier class.
struct Responsibilities {
  int num_points = 0;
  int num_planes = 0;
  std::vector<float> r;
  std::vector<float> range_variance;  // per point: (range_noise * range^2)^2
  std::vector<float> density;         // per plane and point, before normalising: d[j * n + i]

  float At(int plane, int point) const {
    return r[static_cast<size_t>(plane) * num_points + point];
  }
  float Outlier(int point) const { return At(num_planes, point); }
};

// E-step: each point's responsibility for plane j is the Gaussian density of its distance to
// j (variance sigma_j^2 plus the range noise), normalised over all planes and the constant
// outlier density. With `refit`, only the planes flagged in it are evaluated: the others, and
// the points, are those of the previous call on `resp`, whose densities are reused.
void EStep(const Cloud& points, const std::vector<EmPlane>& planes, const Options& options,
           Responsibilities* resp, const std::vector<uint8_t>* refit = nullptr);

// M-step: each plane becomes the weighted least-squares fit of the points — weighted mean and
// the smallest eigenvector of the weighted scatter — and its sigma the weighted RMS distance,
// clamped to [sigma_min, sigma_max]. A plane's normal keeps its previous orientation. With
// `refit`, the planes not flagged in it keep their fit and only get their support.
void MStep(const Cloud& points, const Responsibilities& resp, const Options& options,
           std::vector<EmPlane>* planes, const std::vector<uint8_t>* refit = nullptr);

// Alternates E and M steps until the planes stop moving or `max_iterations`; returns the
// iterations run. A plane that has stopped moving is no longer refitted. `resp` holds the
// responsibilities of the final planes (of the last E-step when EM converged: the planes have
// moved by less than options.em.converged_angle / converged_offset since).
int RunEm(const Cloud& points, const Options& options, int max_iterations,
          std::vector<EmPlane>* planes, Responsibilities* resp);

}  // namespace relplane::segmenter
