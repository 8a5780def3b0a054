#pragma once
// A MapperState built by hand, handed to a step as the parts it takes (as Mapper::Process does).

#include "global_map/inputs.hpp"
#include "global_map/relative_map.hpp"
#include "state.hpp"

namespace relplane::mapper {

// `angular_step` as LearnedFrustum::AngularStep (0: not known).
inline GlobalMapInputs GlobalInputs(const MapperState& state, double angular_step = 0.0) {
  return {state.store, state.comparisons, state.trajectory, state.first_iteration, angular_step};
}

inline RelativeMapInputs RelativeInputs(const MapperState& state) {
  return {state.store, state.comparisons, state.world};
}

}  // namespace relplane::mapper
