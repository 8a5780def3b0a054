#pragma once
// §II.D Relative maps: a group's comparison chain links its rltplanes pairwise; starting from the
// basis rltplane at (0,0,0) every other rltplane gets its relative position and orientation.

#include "comparison/comparison_table.hpp"
#include "global_map/placement.hpp"
#include "global_map/world_map.hpp"
#include "grouping/group.hpp"
#include "plane_store/plane_store.hpp"

namespace relplane::mapper {

// What a group's relative map is built from (§II.C-D): the rltplanes, their comparisons, and the
// global map so far (a chain linked to it is preferred).
struct RelativeMapInputs {
  const PlaneStore& store;
  const ComparisonTable& comparisons;
  const WorldMap& world;
};

// §II.F reordering: the comparison order that uses the most iterations. The basis is the
// member with the most static-edge comparisons, and the chain is the maximum spanning tree over
// static pairings weighted by their common interval (discounted by their spread), which also
// routes around parallel pairs whose static edges are ambiguous (§II.C). Members reached
// through no static pairing are chained by their line (known == kLine) or only their
// orientation (kAngle). A point link needs a static pairing whose spread over all its static
// sub-intervals stays within `comparison.static_std` (§II.C's bound for one sub-interval).
ChainOrder ChooseOrder(const Group& group, const RelativeMapInputs& in,
                       const ComparisonOptions& comparison = {});

// Builds the relative map of `group` from the stored comparisons, along `group.order` once the
// group has been reordered, else along the order chosen now.
RelativeMap BuildRelativeMap(const Group& group, const RelativeMapInputs& in,
                             const ComparisonOptions& comparison = {});

// The position of `plane`'s edge `edge` given a placement of its edge `placement.ref`, using the
// wall's length when it has been seen whole. False when the edges differ and it has not.
bool EdgePoint(const RltPlane& plane, const Placement& placement, int edge, Eigen::Vector2d* point);

}  // namespace relplane::mapper
