#pragma once
// A MapperState built by hand, handed to a step as the parts it takes (as Mapper::Process does).

#include "global_map/inputs.hpp"
#include "global_map/relative_map.hpp"
#include "state.hpp"

namespace relplane::mapper {

inline GlobalMapInputs GlobalInputs(const MapperState& state) {
  return {state.store, state.comparisons, state.trajectory, state.first_iteration,
          state.angular_step};
}

inline RelativeMapInputs RelativeInputs(const MapperState& state) {
  return {state.store, state.comparisons, state.world};
}

}  // namespace relplane::mapper
