#pragma once
// §II.D the map-building step of an iteration: the first group whose relative map is out of date
// (`dirty`) is built again, and the global map re-chained from it (BuildGlobalMap). One group per
// iteration: the next dirty one waits for the next iteration.

#include "global_map/inputs.hpp"
#include "global_map/world_map.hpp"
#include "grouping/group.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

void BuildNextGlobalMap(const GlobalMapInputs& in, const MapperOptions& options, Grouping& grouping,
                        WorldMap& world);

}  // namespace relplane::mapper
