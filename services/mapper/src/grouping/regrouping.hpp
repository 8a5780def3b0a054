#pragma once
// §II.F Groupings and plane comparisons order: "after a constant amount of iterations, a group
// is evaluated for reordering" (its comparison order is chosen to use the most iterations and
// kept); "after another constant amount of iterations, a second evaluation occurs": rltplanes
// with too short a comparison interval are taken out of the group and placed into another
// one, or removed from the map altogether. "The storage [of past untransformed observations]
// is required to be at least as big as it is possible to go back in iterations in the
// regrouping process": a group past that horizon is frozen (its relative map kept, never
// rebuilt) and older observations are dropped, so memory stays flat on long runs.

#include <cstdint>
#include <vector>

#include "comparison/comparison_table.hpp"
#include "global_map/world_map.hpp"
#include "grouping/group.hpp"
#include "plane_store/plane_store.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// Iterations of observations kept: as far back as regrouping reaches (a group is frozen at
// freeze_after; the planes it was made of were co-visible up to covisible_window before).
int64_t ObservationHorizon(const MapperOptions& options);

// One regrouping step at iteration `now`: moves every group that has reached an age to its
// next stage (reorder, regroup, freeze). Changed groups are marked dirty.
// A rltplane taken out of its groups and placed in no other is dropped from every part of the map
// ("removed from the map altogether").
void Regroup(int64_t now, const MapperOptions& options, Grouping& grouping, PlaneStore& store,
             ComparisonTable& comparisons, WorldMap& world);

// Drops the observations regrouping can no longer reach: the visible planes' every iteration,
// every plane's now and then (bounded memory).
void DropOldObservations(const std::vector<int64_t>& visible, int64_t now,
                         const MapperOptions& options, PlaneStore& store);

}  // namespace relplane::mapper
