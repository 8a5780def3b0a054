#pragma once
// Everything the mapper knows, shared by its steps: rltplanes, comparisons, groups and their
// relative maps, the global map and the pose history.

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "relplane/common/geometry.hpp"
#include "comparison/comparison.hpp"
#include "motion/trajectory.hpp"
#include "plane_store/rltplane.hpp"

namespace relplane::mapper {

// How much of a wall's placement is known: its orientation only, its line, or also the position
// of one of its edges (`ref`) along the line.
enum class Known : int { kAngle = 0, kLine = 1, kPoint = 2 };

// A wall placed in a frame (a group's relative frame or the world): frame angle alpha (x along
// the wall), a point on its line (the `ref` edge when known == kPoint).
struct Placement {
  double alpha = 0.0;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  int ref = -1;  // Index(Edge) of the edge `point` is, or -1
  Known known = Known::kAngle;
  // The other edge, when a later group found it static (global map only), and that group.
  bool has_other = false;
  Eigen::Vector2d other = Eigen::Vector2d::Zero();
  int64_t other_by = -1;
  // Relative maps only: variance (m^2) of `point` from the basis, summed over the chain of
  // static pairings that placed it (each pairing's spread over its interval, §II.C).
  double variance = 0.0;
};

// §II.D relative map of one group, in the frame of its basis rltplane.
struct RelativeMap {
  int64_t basis = -1;
  std::map<int64_t, Placement> members;

  // The basis's reference edge (the frame's origin), -1 when it has none or is not placed.
  int BasisRef() const {
    auto it = members.find(basis);
    return it == members.end() ? -1 : it->second.ref;
  }
};

// §II.F the comparison order of a group: the basis, the edge its frame starts at, and which
// placed member each other member is placed from, in placement order.
struct ChainLink {
  int64_t from = -1;
  int64_t to = -1;
};
struct ChainOrder {
  int64_t basis = -1;
  int basis_ref = -1;
  std::vector<ChainLink> links;
};

// Where a group is in §II.F: new (order chosen afresh at every build), reordered (order kept),
// regrouped (short-interval members taken out), frozen (relative map kept, never rebuilt: its
// members' old observations are gone).
enum class GroupStage : int { kNew = 0, kReordered = 1, kRegrouped = 2, kFrozen = 3 };

// §II.B a group of rltplanes seen in the same time interval.
struct Group {
  int64_t id = 0;
  std::vector<int64_t> members;  // in joining order
  int64_t created = 0;           // iteration
  GroupStage stage = GroupStage::kNew;
  ChainOrder order;              // kept from the reordering on (§II.F)
  RelativeMap relative;
  geometry::Pose2 placement;     // world <- group frame (§II.D)
  // The placement hard chaining gave it when it was last placed (§II.D), which a pose graph
  // solve does not change: the centre of the group's prior in the graph (pose_graph.cpp).
  geometry::Pose2 chained;
  bool has_chained = false;
  // Members as seen when the group was made, from the pose then: the basis gives the prior
  // placement, a member placed by orientation only its line. Kept so the group can be placed
  // again after the observations are dropped.
  std::map<int64_t, SeenWall> seen;
  // Members as last seen before the group was made from a pose the walls fixed (invalid when
  // never so seen): the prior along a direction the links leave open (global_map.cpp).
  std::map<int64_t, SeenWall> seen_fixed;
  // Members placed by orientation only, their line as their sightings from poses the walls fixed
  // agree on it (global_map.cpp), with the plane's latest iteration then: kept for the same
  // reason as `seen`, and worked out again only when the plane was seen since.
  std::map<int64_t, std::pair<int64_t, SeenWall>> seen_line;
  // Whether a member's sighting (id, reference end, iteration) shows the wall's end, judged from
  // its sightings before the group was made (global_map.cpp): those do not change, and judging
  // them again at every build cost more than the rest of an iteration.
  std::map<std::tuple<int64_t, int, int64_t>, bool> shows_end;
  // Each member end's (id, reference end) most finely sampled sighting from a pose the walls
  // fixed (group_prior.cpp), with the iteration its observations were scanned to.
  struct FinestEnd {
    SeenWall seen;
    double spacing = 0.0;  // m between the sensor's samples along the wall at that end
    int64_t scanned = -1;  // iteration
    SeenWall previous;     // the last sighting from a fixed pose scanned
  };
  std::map<std::pair<int64_t, int>, FinestEnd> finest_end;
  bool dirty = true;
  int loop_evidence = 0;  // GroupLoopEvidence when last placed (pose_graph.hpp)

  bool Frozen() const { return stage == GroupStage::kFrozen; }
};

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

using PairKey = std::pair<int64_t, int64_t>;
inline PairKey KeyOf(int64_t a, int64_t b) { return a < b ? PairKey{a, b} : PairKey{b, a}; }
struct PairKeyHash {
  size_t operator()(const PairKey& k) const {
    // Plane ids are small and dense: mix the two so neighbouring pairs spread over the buckets.
    const uint64_t h = static_cast<uint64_t>(k.first) * 0x9E3779B97F4A7C15ULL ^
                       static_cast<uint64_t>(k.second) * 0xC2B2AE3D27D4EB4FULL;
    return static_cast<size_t>(h ^ (h >> 29));
  }
};

struct MapperState {
  // rad between the sensor's neighbouring rays as the mapper learnt it (LearnedFrustum), nought
  // while not known: how finely a wall end was sampled.
  double angular_step = 0.0;
  std::map<int64_t, RltPlane> planes;
  // Hashed, not ordered: the relative and global maps look up every pair of a group's members
  // at every build, and a tree's look-ups were most of that time (nothing walks them in order).
  std::unordered_map<PairKey, Comparison, PairKeyHash> comparisons;
  std::vector<Group> groups;                  // index == id
  std::vector<int64_t> ungrouped;             // §II.B ungrouped list, oldest first
  std::set<int64_t> recent;                   // seen within the last-seen window (§II.A)
  std::map<int64_t, Placement> global;        // §II.D global map: plane id -> world placement
  std::map<int64_t, int64_t> placed_by;       // plane id -> group index that placed it
  // Each global plane's orientation as the hard chain placed it, before RefineGlobalOrientations
  // (global_map.hpp) took in the comparisons of the groups after the one that placed it.
  std::map<int64_t, double> chained_alpha;
  Trajectory trajectory;  // the estimated poses (§II.E)
  int64_t next_id = 0;
  int64_t first_iteration = -1;
  size_t open_from = 0;     // groups before this index are frozen (§II.F)
  int64_t last_sweep = -1;  // iteration old observations were last dropped from every plane
  bool map_changed = false;
  int loop_evidence = 0;  // loop-closing ties seen so far (pose_graph.hpp)
  std::vector<PoseTie> pose_ties;  // loops closed by backtracking, the latest 1000
  int pose_ties_made = 0;          // all made so far (each one solves the graph again)
  int graph_solves = 0;   // pose graph solutions run so far

  RltPlane* Plane(int64_t id) {
    auto it = planes.find(id);
    return it == planes.end() ? nullptr : &it->second;
  }
  const RltPlane* Plane(int64_t id) const {
    auto it = planes.find(id);
    return it == planes.end() ? nullptr : &it->second;
  }
  const Comparison* FindComparison(int64_t a, int64_t b) const {
    auto it = comparisons.find(KeyOf(a, b));
    return it == comparisons.end() ? nullptr : &it->second;
  }
  bool InGroup(int64_t plane, int64_t group) const;
};

}  // namespace relplane::mapper
