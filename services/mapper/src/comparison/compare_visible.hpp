#pragma once
// §II.C the comparison step: every pair of rltplanes seen now that share a group is compared
// again (their relative orientation, the edges' pairings over sub-intervals, the static edges).

#include <cstdint>
#include <set>
#include <vector>

#include "comparison/comparison_table.hpp"
#include "grouping/group.hpp"
#include "plane_store/plane_store.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// `visible` sorted. Compares each pair of them that shares a group and resets the planes'
// static-now flags for this iteration. Returns the groups whose relative map is to be built again
// (§II.D): those holding a compared pair, but not frozen ones, whose relative map is kept (§II.F).
std::set<int64_t> CompareVisible(int64_t iteration, const std::vector<int64_t>& visible,
                                 const MapperOptions& options, const Grouping& grouping,
                                 PlaneStore& store, ComparisonTable& comparisons);

}  // namespace relplane::mapper
