#pragma once
// The global map (§II.D): where every placed wall is in the world, which group placed it, and
// the loops closed by backtracking that tie groups together.

#include <cstdint>
#include <map>
#include <vector>

#include "global_map/placement.hpp"
#include "relplane/common/geometry.hpp"

namespace relplane::mapper {

// A loop closing through backtracking (§II.A end): at one iteration the sensor pose as the
// drifting chain had it (`a`, in group `a_group`'s frame, from the walls that chain placed) and
// as the re-seen old walls put it (`b`, in group `b_group`'s frame). The same pose: the pose graph
// (pose_graph.hpp) holds the two groups to it, so the error the loop reveals is spread over the
// groups between them. Without it nothing tied them where the closing group shared no wall end
// with the chain's last group (turning in place at a corner, the walls before the turn out of
// view before the old ones came in): the jump of the pose was the only trace of the loop's error.
// Each group's frame is its basis's (with the basis's reference edge): a tie whose group was
// based anew since is left out.
struct PoseTie {
  int64_t a_group = -1;
  int64_t b_group = -1;
  int64_t a_basis = -1;
  int64_t b_basis = -1;
  int a_ref = -1;
  int b_ref = -1;
  geometry::Pose2 a;
  geometry::Pose2 b;
  // The chain's walls left the position open along direction open_alpha (in group a's frame),
  // and the sensor was moving: the tie holds nothing along it.
  bool has_open = false;
  double open_alpha = 0.0;
};

// Owned by the global-map step (§II.D); registration reads it to match old walls (§II.A end) and
// adds loop-closing ties (loop_closure.hpp).
struct WorldMap {
  std::map<int64_t, Placement> global;   // plane id -> world placement
  std::map<int64_t, int64_t> placed_by;  // plane id -> group index that placed it
  // Each global plane's orientation as the hard chain placed it, before RefineGlobalOrientations
  // (global_map.hpp) took in the comparisons of the groups after the one that placed it.
  std::map<int64_t, double> chained_alpha;
  bool changed = false;
  int loop_evidence = 0;           // loop-closing ties seen so far (pose_graph.hpp)
  std::vector<PoseTie> pose_ties;  // loops closed by backtracking, the latest 1000
  int pose_ties_made = 0;          // all made so far (each one solves the graph again)
  int graph_solves = 0;            // pose graph solutions run so far

  // Takes rltplane `id` off the map (it left it, §II.F).
  void Forget(int64_t id) {
    global.erase(id);
    placed_by.erase(id);
    chained_alpha.erase(id);
    changed = true;
  }
};

}  // namespace relplane::mapper
