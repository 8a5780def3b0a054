#pragma once
// §II.C the comparison step: every pair of rltplanes seen now that share a group is compared
// again (their relative orientation, the edges' pairings over sub-intervals, the static edges).

#include <cstdint>
#include <vector>

#include "relplane/mapper/options.hpp"
#include "state.hpp"

namespace relplane::mapper {

// `visible` sorted. Marks the groups of each compared pair to be built again (not frozen ones,
// whose relative map is kept, §II.F) and resets the planes' static-now flags for this iteration.
void CompareVisible(int64_t iteration, const std::vector<int64_t>& visible,
                    const MapperOptions& options, MapperState& state);

}  // namespace relplane::mapper
