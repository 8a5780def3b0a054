#include "global_map/build_maps.hpp"

#include "global_map/global_map.hpp"

namespace relplane::mapper {

void BuildNextGlobalMap(MapperState& state, const MapperOptions& options) {
  for (size_t g = 0; g < state.groups.size(); ++g) {
    if (state.groups[g].dirty) {
      BuildGlobalMap(state, g, options);
      return;
    }
  }
}

}  // namespace relplane::mapper
