#pragma once
// Everything the mapper knows, as the parts its steps own: the planes (registration, §II.A), the
// comparisons (§II.C), the groups (§II.B, §II.F), the global map (§II.D) and the trajectory
// (§II.E). A step takes the parts it writes by reference and the others const.

#include <cstdint>

#include "comparison/comparison_table.hpp"
#include "global_map/world_map.hpp"
#include "grouping/group.hpp"
#include "motion/trajectory.hpp"
#include "plane_store/plane_store.hpp"

namespace relplane::mapper {

struct MapperState {
  PlaneStore store;
  ComparisonTable comparisons;
  Grouping grouping;
  WorldMap world;
  Trajectory trajectory;
  int64_t first_iteration = -1;
};

}  // namespace relplane::mapper
