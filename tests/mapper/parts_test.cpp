// The parts of what the mapper knows (state.hpp) each forget a rltplane that leaves the map
// (§II.F "removed from the map altogether") without touching the others' planes.

#include <gtest/gtest.h>

#include "ideal_segmenter.hpp"
#include "state.hpp"

namespace relplane::mapper {
namespace {

RltPlane PlaneSeen(int64_t id) {
  return RltPlane(id, *MakeObservation(testing::WallSeen({2, -1}, {2, 1}), 0, 0.3), 0.05, 100);
}

TEST(Parts, EachForgetsTheLeavingPlaneOnly) {
  MapperState state;
  for (int64_t id : {3, 4}) {
    state.store.planes.emplace(id, PlaneSeen(id));
    state.store.recent.insert(id);
    state.grouping.ungrouped.push_back(id);
    state.world.global[id] = Placement{};
    state.world.placed_by[id] = 0;
    state.world.chained_alpha[id] = 0.0;
  }
  state.comparisons.pairs.try_emplace(KeyOf(3, 4), 3, 4);
  state.comparisons.pairs.try_emplace(KeyOf(4, 7), 4, 7);

  state.store.Forget(3);
  state.comparisons.Forget(3);
  state.grouping.Forget(3);
  state.world.Forget(3);

  EXPECT_EQ(state.store.Plane(3), nullptr);
  EXPECT_NE(state.store.Plane(4), nullptr);
  EXPECT_EQ(state.store.recent, (std::set<int64_t>{4}));
  EXPECT_EQ(state.comparisons.Find(3, 4), nullptr);
  EXPECT_NE(state.comparisons.Find(7, 4), nullptr);
  EXPECT_EQ(state.grouping.ungrouped, (std::vector<int64_t>{4}));
  EXPECT_EQ(state.world.global.count(3), 0u);
  EXPECT_EQ(state.world.placed_by.count(3), 0u);
  EXPECT_EQ(state.world.chained_alpha.count(3), 0u);
  EXPECT_EQ(state.world.global.count(4), 1u);
  EXPECT_TRUE(state.world.changed);  // the published map changed
}

TEST(Parts, MarkDirtyFlagsTheNamedGroups) {
  Grouping grouping;
  grouping.groups.resize(3);
  for (Group& g : grouping.groups) g.dirty = false;
  grouping.MarkDirty({0, 2});
  EXPECT_TRUE(grouping.groups[0].dirty);
  EXPECT_FALSE(grouping.groups[1].dirty);
  EXPECT_TRUE(grouping.groups[2].dirty);
}

}  // namespace
}  // namespace relplane::mapper
