// The grid the published map's clean-up and corner snapping find nearby walls with: a query
// returns every box that may overlap it, each once, in increasing order.
#include "published_map/box_grid.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace relplane::mapper {
namespace {

using Box = Eigen::AlignedBox2d;
using Eigen::Vector2d;

TEST(BoxGrid, AQueryFindsEveryOverlappingBoxOnceInOrder) {
  BoxGrid grid(2.0);
  grid.Insert(0, Box(Vector2d(0, 0), Vector2d(15, 0.2)));      // a long wall over 8 cells
  grid.Insert(1, Box(Vector2d(14.9, -3), Vector2d(15.1, 3)));  // crossing it at its end
  grid.Insert(2, Box(Vector2d(40, 40), Vector2d(41, 41)));     // far away
  grid.Insert(3, Box(Vector2d(-3.1, -0.1), Vector2d(-2.9, 0.1)));
  EXPECT_EQ(grid.Query(Box(Vector2d(14.8, -0.1), Vector2d(15.2, 0.1))),
            (std::vector<size_t>{0, 1}));
  EXPECT_EQ(grid.Query(Box(Vector2d(7, 0), Vector2d(7, 0))), (std::vector<size_t>{0}));
  EXPECT_EQ(grid.Query(Box(Vector2d(-3, 0), Vector2d(-3, 0))), (std::vector<size_t>{3}));
  EXPECT_TRUE(grid.Query(Box(Vector2d(100, 100), Vector2d(101, 101))).empty());
}

TEST(BoxGrid, BoxesAcrossZeroAndOnCellBordersAreFound) {
  BoxGrid grid(1.0);
  grid.Insert(0, Box(Vector2d(-0.5, -0.5), Vector2d(0.5, 0.5)));
  grid.Insert(1, Box(Vector2d(2.0, 2.0), Vector2d(2.0, 2.0)));
  EXPECT_EQ(grid.Query(Box(Vector2d(-0.1, -0.1), Vector2d(-0.1, -0.1))), (std::vector<size_t>{0}));
  EXPECT_EQ(grid.Query(Box(Vector2d(1.99, 1.99), Vector2d(2.0, 2.0))), (std::vector<size_t>{1}));
}

TEST(BoxGrid, BoxesTooWideOrNotFiniteAreMetByEveryQuery) {
  BoxGrid grid(1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  grid.Insert(0, Box(Vector2d(0, 0), Vector2d(1e7, 1e7)));
  grid.Insert(1, Box(Vector2d(nan, 0), Vector2d(nan, 1)));
  grid.Insert(2, Box(Vector2d(5, 5), Vector2d(5, 5)));
  EXPECT_EQ(grid.Query(Box(Vector2d(-50, -50), Vector2d(-49, -49))), (std::vector<size_t>{0, 1}));
  // A query as wide as the world meets everything.
  EXPECT_EQ(grid.Query(Box(Vector2d(-1e9, -1e9), Vector2d(1e9, 1e9))),
            (std::vector<size_t>{0, 1, 2}));
}

}  // namespace
}  // namespace relplane::mapper
