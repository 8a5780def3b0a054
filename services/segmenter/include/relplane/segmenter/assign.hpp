#pragma once
// The single pass over every point of the cloud after EM has converged on a subsample.

#include <cstdint>
#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/em.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter {

// Labels each point with the plane it is closest to in units of that plane's sigma, when within
// options.assignment.inlier_sigmas; -1 otherwise (outlier). The hard counterpart of the E-step.
// `ambiguous` (optional) marks points within the inlier band of two or more crossing planes:
// the strip along the line where two planes meet. The vectors' buffers are reused.
void AssignPoints(const Cloud& cloud, const std::vector<EmPlane>& planes, const Options& options,
                  std::vector<int32_t>* labels, std::vector<uint8_t>* ambiguous = nullptr);

}  // namespace relplane::segmenter
