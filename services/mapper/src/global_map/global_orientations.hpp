#pragma once
// §V soft-linked orientations on the global map: every comparison between mapped planes turns
// them, not only the group's that placed each one.

#include <cstddef>

#include "global_map/inputs.hpp"
#include "global_map/world_map.hpp"
#include "grouping/group.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// Soft-linked orientations (the paper's future work, §V): each global plane's orientation from
// every comparison between planes on the global map, not only those of the group that placed
// it, the first group's planes held. A wall first seen through a door is placed by a group whose
// only comparisons with the walls already mapped are short pieces beside the door, fitted off
// the same way on one side; a later group holding the jamb on the other side balances them.
// Only the planes groups `from`, `from + 1`, ... placed are solved, against the others as they
// stand: the map grows with the run while what one iteration re-places does not.
void RefineGlobalOrientations(const GlobalMapInputs& in, const Grouping& grouping, size_t from,
                              const GlobalMapOptions& options, WorldMap& world);

}  // namespace relplane::mapper
