#pragma once
// §II.B Grouping planes: rltplanes are grouped by visibility. A new rltplane waits in the
// ungrouped list until it has enough observations (or times out and is dropped), then joins a
// recent group whose members were all seen in the same interval, or opens a new group that also
// holds the co-visible rltplanes of the previous groups (the link planes that chain the
// group's relative map to the global map, §II.D).

#include <cstdint>
#include <vector>

#include "grouping/group.hpp"
#include "plane_store/plane_store.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// Iterations among the last `window` (up to `now`) in which both planes were observed.
int CommonRecent(const RltPlane& a, const RltPlane& b, int64_t now, int window);
// Stored observations of both planes at the same iteration, from iteration `from` on.
int CommonSince(const RltPlane& a, const RltPlane& b, int64_t from);

// One grouping step at iteration `now`: the rltplanes registration `created` join the ungrouped
// list (§II.B); `visible` are the rltplanes observed this iteration. Groups that gain members are
// marked dirty; timed-out ungrouped rltplanes are erased from the store.
void UpdateGroups(const std::vector<int64_t>& created, const std::vector<int64_t>& visible,
                  int64_t now, const GroupingOptions& options, Grouping& grouping,
                  PlaneStore& store);

}  // namespace relplane::mapper
