#include "global_map/global_orientations.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <vector>

#include "comparison/comparison.hpp"

namespace relplane::mapper {

void RefineGlobalOrientations(const GlobalMapInputs& in, const Grouping& grouping, size_t from,
                              const GlobalMapOptions& options, WorldMap& world) {
  // Least squares on the corrections from the chained orientations, as RefineOrientations does
  // within a group, over every comparison between two planes on the global map; the first
  // group's planes are held (§II.D: it is placed from the start pose). Hard chaining (§II.D)
  // gives a wall its orientation from the one group that placed it, through that group's
  // comparisons only. A group made at a door holds the walls of the next room and, of the room
  // it leaves, only the short pieces beside the door, whose fits are off by a degree or more
  // towards the door, mirrored on its two sides (a piece takes some of the jamb's points): where
  // it holds more pieces of one side (both pieces of the wall and one jamb, the other jamb in the
  // group before), the next room's walls come out a fraction of a degree off, and every later
  // group and pose with them. The other side's comparisons with those walls are there, in other
  // groups, and balance them. Anchored at the chained values rather than at the last solution,
  // so solving again after every placement does not walk the orientations away (as
  // pose_graph.cpp's priors).
  // The planes placed before `from` were not re-placed: they are held as last solved.
  // Called before every re-placed group is solved (BuildGlobalMap): the cost follows those
  // groups, not the map, and sorted vectors stand in for trees.
  std::vector<int64_t> ids;
  for (size_t g = std::max<size_t>(from, 1); g < grouping.groups.size(); ++g) {
    for (const auto& [id, rel] : grouping.groups[g].relative.members) {
      const auto by = world.placed_by.find(id);
      if (by == world.placed_by.end() || static_cast<size_t>(by->second) != g) continue;
      if (world.chained_alpha.count(id)) ids.push_back(id);
    }
  }
  std::sort(ids.begin(), ids.end());
  const int n = static_cast<int>(ids.size());
  if (n == 0) return;
  auto index_of = [&](int64_t id) {
    const auto it = std::lower_bound(ids.begin(), ids.end(), id);
    return it != ids.end() && *it == id ? static_cast<int>(it - ids.begin()) : -1;
  };
  // A solved plane from its chained orientation, a held one as it stands.
  auto value = [&](int64_t id, int k) {
    return k >= 0 ? world.chained_alpha.at(id) : world.global.at(id).alpha;
  };
  // Sparse: a plane is compared only with the members of its groups (§II.C).
  std::vector<PairKey> pairs;
  for (int64_t id : ids) {
    for (int64_t g : in.store.Plane(id)->groups) {
      for (int64_t other : grouping.groups[g].members) {
        if (other != id) pairs.push_back(KeyOf(id, other));
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<Eigen::Triplet<double>> a;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  for (const PairKey& key : pairs) {
    const Comparison* cmp = in.comparisons.Find(key.first, key.second);
    if (cmp == nullptr || !world.global.count(key.first) || !world.global.count(key.second)) {
      continue;
    }
    const double w = cmp->PieceInformation();
    if (w <= 0.0) continue;
    const int x = index_of(key.first), y = index_of(key.second);
    const double r = geometry::WrapAngle(value(key.second, y) - value(key.first, x) -
                                         cmp->PieceAlpha(key.first));
    if (y >= 0) a.emplace_back(y, y, w), b(y) -= w * r;
    if (x >= 0) a.emplace_back(x, x, w), b(x) += w * r;
    if (x >= 0 && y >= 0) a.emplace_back(x, y, -w), a.emplace_back(y, x, -w);
  }
  // A weak prior at the chained value: the gauge of planes no comparison ties to the held ones.
  for (int k = 0; k < n; ++k) a.emplace_back(k, k, options.chained_orientation_prior);
  Eigen::SparseMatrix<double> h(n, n);
  h.setFromTriplets(a.begin(), a.end());  // duplicates are summed
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(h);
  if (solver.info() != Eigen::Success) return;
  const Eigen::VectorXd dx = solver.solve(b);
  if (!dx.allFinite()) return;
  for (int k = 0; k < n; ++k) {
    world.global.at(ids[k]).alpha = geometry::WrapAngle(value(ids[k], k) + dx(k));
  }
}

}  // namespace relplane::mapper
