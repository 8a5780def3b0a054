#pragma once
// §II.D the map-building step of an iteration: the first group whose relative map is out of date
// (`dirty`) is built again, and the global map re-chained from it (BuildGlobalMap). One group per
// iteration: the next dirty one waits for the next iteration.

#include "relplane/mapper/options.hpp"
#include "state.hpp"

namespace relplane::mapper {

void BuildNextGlobalMap(MapperState& state, const MapperOptions& options);

}  // namespace relplane::mapper
