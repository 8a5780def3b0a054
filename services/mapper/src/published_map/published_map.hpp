#pragma once
// The published map (MAP): each global-map wall placed with its line (§II.D) drawn as a
// rectangle between its ends, cleaned up (duplicates merged, ends drawn at corners), and the
// groups.

#include "relplane/mapper/options.hpp"
#include "relplane/mapper/types.hpp"
#include "state.hpp"

namespace relplane::mapper {

MapSnapshot PublishedMap(const MapperState& state, const MapperOptions& options);

}  // namespace relplane::mapper
