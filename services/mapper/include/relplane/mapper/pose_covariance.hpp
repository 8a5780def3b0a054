#pragma once
// The covariance published with each pose (pose_t.covariance): the observability of what the
// frame's localisation used (observability.hpp).

#include "relplane/mapper/observability.hpp"
#include "relplane/mapper/types.hpp"

namespace relplane::mapper {

// From the position information the solve's walls and ends gave (m^-2) and the heading's sigma. The
// heading is solved first and the position given it (§II.D), so the two are taken as uncorrelated.
// A pose no wall fixed (initializing, lost) has the prior's covariance.
Observability ObservabilityOf(const PoseEstimate& estimate,
                              const ObservabilityOptions& options = {});

}  // namespace relplane::mapper
