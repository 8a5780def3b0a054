#include "global_map/build_maps.hpp"

#include "global_map/global_map.hpp"

namespace relplane::mapper {

void BuildNextGlobalMap(const GlobalMapInputs& in, const MapperOptions& options, Grouping& grouping,
                        WorldMap& world) {
  for (size_t g = 0; g < grouping.groups.size(); ++g) {
    if (grouping.groups[g].dirty) {
      BuildGlobalMap(in, g, options, grouping, world);
      return;
    }
  }
}

}  // namespace relplane::mapper
