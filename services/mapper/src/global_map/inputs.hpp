#pragma once
// What the global-map step (§II.D) reads of the parts other steps own: it writes only the groups'
// placements and caches and the world map.

#include <cstdint>

#include "comparison/comparison_table.hpp"
#include "motion/trajectory.hpp"
#include "plane_store/plane_store.hpp"

namespace relplane::mapper {

struct GlobalMapInputs {
  const PlaneStore& store;
  const ComparisonTable& comparisons;
  const Trajectory& trajectory;
  int64_t first_iteration = -1;  // the start pose's iteration (the map's anchor)
  // rad between the sensor's neighbouring rays as learnt (LearnedFrustum), nought while not known.
  double angular_step = 0.0;
};

}  // namespace relplane::mapper
