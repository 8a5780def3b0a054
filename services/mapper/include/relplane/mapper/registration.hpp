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

// After matching: an end seen uncut now that lies far from where the same rltplane's end was
// last seen uncut (both placed on the map with the poses then and now, over the last few
// seconds) is another end, not the wall's: a wall seen whole (a door wall from across the
// room) is later seen in pieces, and the piece continuing it has a new end at the door; or a
// piece grows into the whole wall. Such an end is marked cut, so it never becomes the static
// edge (§II.C) the rltplane learnt at the other place: the end mapped metres away would be
// taken for it. `pose` is the latest estimate (one frame's motion is far below the jump).
void MarkJumpedEnds(const std::vector<int64_t>& match, const MapperState& state,
                    const geometry::Pose2& pose, std::vector<Observation>* observations);

}  // namespace relplane::mapper
