#pragma once
// §II.B Grouping planes: rltplanes are grouped by visibility. A new rltplane waits in the
// ungrouped list until it has enough observations (or times out and is dropped), then joins a
// recent group whose members were all seen in the same interval, or opens a new group that also
// holds the co-visible rltplanes of the previous groups (the link planes that chain the
// group's relative map to the global map, §II.D).

#include <cstdint>
#include <vector>

#include "relplane/mapper/options.hpp"
#include "state.hpp"

namespace relplane::mapper {

// Iterations among the last `window` (up to `now`) in which both planes were observed.
int CommonRecent(const RltPlane& a, const RltPlane& b, int64_t now, int window);
// Stored observations of both planes at the same iteration, from iteration `from` on.
int CommonSince(const RltPlane& a, const RltPlane& b, int64_t from);

// One grouping step at iteration `now`. `visible` are the rltplanes observed this iteration.
// Groups that gain members are marked dirty; timed-out ungrouped rltplanes are erased.
void UpdateGroups(MapperState& state, const std::vector<int64_t>& visible, int64_t now,
                  const GroupingOptions& options);

}  // namespace relplane::mapper
