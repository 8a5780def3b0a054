#pragma once
// §II.A Registering planes: each untransformed plane of this iteration is matched against the
// latest untransformed observation of recently seen rltplanes.

#include <cstdint>
#include <vector>

#include "relplane/mapper/observation.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/state.hpp"

namespace relplane::mapper {

// The score of matching `obs` to a rltplane whose latest observation is `latest`, or a negative
// number when a test fails: last seen within the window, plane equations within bounds,
// sufficient bounding-box overlap. Higher is better (each test adds how well it passed).
double MatchScore(const Observation& latest, const Observation& obs,
                  const RegistrationOptions& options);

// For each observation, the id of the rltplane it registers to, or -1 (a new rltplane). Only
// rltplanes in `state.recent` are compared, so the cost does not grow with the map. Each
// rltplane takes at most one observation; the highest scores are assigned first.
std::vector<int64_t> RegisterObservations(const std::vector<Observation>& observations,
                                          const MapperState& state,
                                          const RegistrationOptions& options);

}  // namespace relplane::mapper
