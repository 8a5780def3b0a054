#pragma once
// §II.D the map-building step of an iteration: the global map is chained again from the first
// group whose relative map is out of date (`dirty`), and that group and every later dirty one
// are built again on the way (BuildGlobalMap): hard chaining moves every group after one that
// moved.

#include "global_map/inputs.hpp"
#include "global_map/world_map.hpp"
#include "grouping/group.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

void BuildNextGlobalMap(const GlobalMapInputs& in, const MapperOptions& options, Grouping& grouping,
                        WorldMap& world);

}  // namespace relplane::mapper
