#include "global_map/global_map.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "comparison/comparison.hpp"
#include "global_map/group_prior.hpp"
#include "global_map/pose_graph.hpp"
#include "global_map/relative_map.hpp"
#include "localisation/least_squares.hpp"
#include "localisation/pose_solver.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;
using geometry::Pose2;

// How much a line placed in a relative map by its orientation (Known::kLine) counts where the
// wall stands, `lever` metres along it from where its offset was measured: its fit's noise and a
// short piece's orientation bias over the lever, against `global_map.full_line`.
double LineWeight(double lever, double length, const MapperOptions& options) {
  const double bias = PieceBlurOfLength(length, options.fit);
  const double sigma = std::hypot(options.global_map.line_noise, lever * bias);
  const double full = options.global_map.full_line;
  return std::min(1.0, (full * full) / (sigma * sigma));
}

// Does the plane's first sighting show the end `ref` its relative map starts from? Only if the
// latest uncut sighting of that end from a known pose lies where the first one did. A wall seen
// whole across a door from the start pose (its edges where the view cut it, before the view was
// learnt) is later known by the door-side end of its piece: that end lies metres along the wall
// from the first sighting's, and the first group, placed from the first sighting's end, would
// be off by as much (§II.D: the first group is placed from its members' first sightings).
bool FirstSightingShowsEnd(const Trajectory& trajectory, const RltPlane& plane,
                           const SeenWall& first, int ref, double agreement) {
  if (ref < 0 || first.cut[ref]) return false;
  const auto& all = plane.Observations();
  const Vector2d t = DirectionOf(first.alpha);
  for (size_t i = all.size(); i > 0; --i) {
    const Observation& obs = all[i - 1];
    const auto pose = trajectory.poses.find(obs.iteration);
    if (obs.cut[ref] || pose == trajectory.poses.end()) continue;
    return std::abs(t.dot(pose->second * obs.edge[ref] - first.edge[ref])) <= agreement;
  }
  return true;  // nothing seen since contradicts it
}

struct Link {
  Placement relative;
  Placement global;
  const RltPlane* plane;
  // rad^-2: how well `global`'s orientation is known where it is one sighting (the first
  // group's); 0: as well as the plane's best fit (OrientationWeight).
  double orientation_weight = 0.0;
};

// The orientation weight of a plane's sighting at `iteration`: its fit's noise and, as a single
// fit is not averaged over an interval, a short piece's bias over its length (PieceBlur). 0 when
// the observation is gone.
double SightingOrientationWeight(const RltPlane& plane, int64_t iteration) {
  const auto& all = plane.Observations();
  const size_t i = plane.LowerBound(iteration);
  if (i >= all.size() || all[i].iteration != iteration) return 0.0;
  const ObservationTerms& terms = plane.Terms(i);  // OrientationWeight and PieceBlur
  return 1.0 / (1.0 / terms.weight + terms.blur * terms.blur);
}

// Least squares for world <- group: rotation from the mean orientation difference, translation
// from the links' lines (1 equation each) and shared static edges (1 more along the wall).
Pose2 Solve(const std::vector<Link>& links, const Prior& prior_in, const MapperOptions& options) {
  const double prior_weight = options.localisation.prior_weight;
  const Pose2& prior = prior_in.pose;
  double s = 0.0, c = 0.0;
  for (const Link& l : links) {
    // Weighted by how well each wall's fit fixes its orientation, as in localisation: a door
    // jamb must not turn a group of walls metres long.
    const double w =
        l.orientation_weight > 0.0 ? l.orientation_weight : OrientationWeight(*l.plane);
    const double d = l.global.alpha - l.relative.alpha;
    s += w * std::sin(d), c += w * std::cos(d);
  }
  const double yaw = links.empty() ? prior.yaw : std::atan2(s, c);
  const Matrix2d rot = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  // A link's two lines are compared where the wall is (its latest sighting, as the pose then
  // put it), not at the point of the group's line: that is the foot of the perpendicular from
  // the edge the line was measured from (relative_map.cpp PlaceLine), which may lie metres along
  // the line, where the two lines' slightly different orientations part. `guess` is the
  // translation that looks the wall up in the group's frame: centimetres off move the point by
  // as much along the line, where the lines nearly agree.
  // Each line is weighed by how well its offset is known where the wall is: its fit's noise, and
  // a short piece's orientation bias (3 cm over its length) carried over the distance from the
  // edge it was measured from. A line known within `global_map.full_line` counts fully, as every
  // line did: a short pilaster side, fitted a degree off and measured from a recess corner metres
  // along its line, is centimetres off where it stands, and once it is its group's link it decides
  // the group's position along a hallway (the static edge that decided it before is only used where
  // the lines leave a direction open), moving the group and the pose back by as much.
  auto lines_at = [&](const Vector2d& guess, Matrix2d* a, Vector2d* b) {
    *a = Matrix2d::Zero();
    *b = Vector2d::Zero();
    for (const Link& l : links) {
      if (l.relative.known == Known::kAngle || l.global.known == Known::kAngle) continue;
      const Vector2d n = NormalOf(l.global.alpha);
      Vector2d at = l.relative.point;
      double weight = 1.0;
      if (l.relative.known == Known::kLine && l.plane->latest_pose_known) {
        const Observation& latest = l.plane->Latest();
        const Vector2d wall = l.plane->latest_pose * (0.5 * (latest.edge[0] + latest.edge[1]));
        const Vector2d d = DirectionOf(l.relative.alpha);
        const double lever = d.dot(rot.transpose() * (wall - guess) - l.relative.point);
        at += d * lever;
        weight = LineWeight(lever, l.plane->Length(), options);
      }
      *a += weight * n * n.transpose();
      *b += weight * n * n.dot(l.global.point - rot * at);
    }
  };
  Matrix2d a;
  Vector2d b;
  lines_at(prior.Translation(), &a, &b);
  if (Eigen::SelfAdjointEigenSolver<Matrix2d>(a).eigenvalues()(0) >= 0.5) {
    lines_at(a.ldlt().solve(b), &a, &b);  // once more from where the lines put the group
  }
  // The prior only decides a direction the links leave open; along the directions its members'
  // lines span, those lines as seen with the heading the links give, its ends' placement along
  // the rest.
  Vector2d prior_t = prior.Translation();
  if (!prior_in.lines.empty()) {
    Matrix2d la = Matrix2d::Zero();
    Vector2d lb = Vector2d::Zero();
    for (const PriorLine& line : prior_in.lines) {
      const Vector2d n = NormalOf(yaw + line.member.alpha);
      // Weighed as the links' lines are: a door jamb's line, placed through a comparison with the
      // room's far wall where the two cross metres away, is centimetres off where the jamb
      // stands; counted as fully as the room's side walls, it moves the group, the pose and the
      // room's walls across the room when the group's basis changes. A direction only such
      // lines span, below `localisation.open_information`, is left to the ends' placement.
      double weight = 1.0;
      if (line.member.known == Known::kLine) {
        const Vector2d d = DirectionOf(line.member.alpha);
        const double lever =
            d.dot(rot.transpose() * (line.seen_point - prior.Translation()) - line.member.point);
        weight = LineWeight(lever, line.length, options);
      }
      la += weight * n * n.transpose();
      lb += weight * n * n.dot(line.seen_point - rot * line.member.point);
    }
    prior_t = SolveWithPrior(la, lb, prior_t, 0.0, 0.0, options.localisation.open_information);
  }
  // Lines are exact whatever the edges do; static edges are added only where the lines leave
  // a direction open (parallel walls), since an edge taken for static may not quite be. One
  // link's edge each, unless some agree with the prior along their wall and others lie more
  // than `global_map.edge_gate` from it: those are dropped. Where one link's piece in the group's
  // relative map is paired at the wrong end (a hallway wall whose end next to a recess is taken for
  // its far end), the two edges of a group's links put it a wall's length apart, and their mean
  // moves the group and the pose half that along the hallway in one iteration.
  Eigen::SelfAdjointEigenSolver<Matrix2d> eig(a);
  if (eig.eigenvalues()(0) < 0.5) {
    struct EdgeTie {
      Vector2d along;        // the wall's direction
      Vector2d translation;  // the group's translation the edge puts it at
    };
    std::vector<EdgeTie> ties;
    for (const Link& l : links) {
      if (l.relative.known == Known::kAngle || l.global.known == Known::kAngle) continue;
      for (int e = 0; e < 2; ++e) {
        Vector2d rel_point, global_point;
        if (!EdgePoint(*l.plane, l.global, e, &global_point) ||
            !EdgePoint(*l.plane, l.relative, e, &rel_point)) {
          continue;
        }
        ties.push_back({DirectionOf(l.global.alpha), global_point - rot * rel_point});
        break;
      }
    }
    auto agrees = [&](const EdgeTie& tie) {
      return std::abs(tie.along.dot(tie.translation - prior_t)) <= options.global_map.edge_gate;
    };
    const bool any_agrees = std::any_of(ties.begin(), ties.end(), agrees);
    for (const EdgeTie& tie : ties) {
      if (any_agrees && !agrees(tie)) continue;
      a += tie.along * tie.along.transpose();
      b += tie.along * tie.along.dot(tie.translation);
    }
  }
  const Vector2d t =
      SolveWithPrior(a, b, prior_t, prior_weight, 0.5, options.localisation.open_information);
  return {t.x(), t.y(), yaw};
}

Placement Apply(const Pose2& pose, const Placement& p) {
  Placement out = p;
  out.alpha = geometry::WrapAngle(pose.yaw + p.alpha);
  out.point = pose * p.point;
  return out;
}

}  // namespace

Placement PlacementOf(const SeenWall& seen, int ref) {
  Placement p;
  p.alpha = seen.alpha;
  p.point = ref >= 0 ? seen.edge[ref] : 0.5 * (seen.edge[0] + seen.edge[1]);
  p.ref = ref;
  p.known = ref >= 0 ? Known::kPoint : Known::kLine;
  return p;
}

SeenWall EndSeenFromFixedPoses(const Trajectory& trajectory, const RltPlane& plane, int ref) {
  SeenWall latest;
  if (ref < 0) return latest;
  std::vector<double> along;  // each sighting's end, along the wall from the latest one's
  const auto& all = plane.Observations();
  for (size_t i = all.size(); i > 0; --i) {
    const Observation& obs = all[i - 1];
    const auto pose = trajectory.poses.find(obs.iteration);
    if (obs.cut[ref] || pose == trajectory.poses.end() ||
        trajectory.fixed.count(obs.iteration) == 0) {
      continue;
    }
    const SeenWall seen = SeenFrom(obs, pose->second);
    if (!latest.valid) latest = seen;
    along.push_back(DirectionOf(latest.alpha).dot(seen.edge[ref] - latest.edge[ref]));
  }
  if (!latest.valid) return latest;
  std::sort(along.begin(), along.end());
  const size_t n = along.size();
  const double median = n % 2 == 1 ? along[n / 2] : 0.5 * (along[n / 2 - 1] + along[n / 2]);
  latest.edge[ref] += median * DirectionOf(latest.alpha);
  return latest;
}

Placement PlacementOf(const Observation& obs, const Pose2& pose, int ref) {
  return PlacementOf(SeenFrom(obs, pose), ref);
}

void WallEnds(const Trajectory& trajectory, const RltPlane& plane, const Placement& placed,
              Vector2d* lo_out, Vector2d* hi_out) {
  const Vector2d t = DirectionOf(placed.alpha);
  const double length = plane.Length();
  Vector2d lo, hi;
  if (placed.known == Known::kPoint && placed.has_other) {
    lo = placed.ref == 0 ? placed.point : placed.other;
    hi = placed.ref == 0 ? placed.other : placed.point;
  } else if (placed.known == Known::kPoint && placed.ref == 1) {
    hi = placed.point, lo = hi - length * t;
  } else if (placed.known == Known::kPoint) {
    lo = placed.point, hi = lo + length * t;
  } else {
    lo = hi = placed.point;
    // Its extent as last seen, from the pose then.
    const Observation& last = plane.Latest();
    auto pose = trajectory.poses.find(last.iteration);
    if (pose != trajectory.poses.end() || plane.latest_pose_known) {
      const Pose2& from = pose != trajectory.poses.end() ? pose->second : plane.latest_pose;
      const Vector2d a = from * last.edge[0], b = from * last.edge[1];
      lo = placed.point + t * t.dot(a - placed.point);
      hi = placed.point + t * t.dot(b - placed.point);
      if (t.dot(hi - lo) < 0) std::swap(lo, hi);
    }
  }
  *lo_out = lo;
  *hi_out = hi;
}

// Places the members of group `g` not yet on the global map (hard rule: the first group to
// place a plane wins, unless a later one knows more), from the group's placement.
void PlaceMembers(const GlobalMapInputs& in, Group& group, const MapperOptions& options,
                  WorldMap& world) {
  for (const auto& [id, rel] : group.relative.members) {
    // Kept now, while the observation is there, for when this group places it.
    if (rel.known == Known::kAngle) LineWhenMade(in, group, id, options);
    auto it = world.global.find(id);
    // Hard chaining: the first group to place a plane wins, unless a later one knows more.
    // A later group that found the plane's other edge static adds that end to the map.
    if (it != world.global.end() && it->second.known >= rel.known) {
      Placement& placed = it->second;
      if (placed.known == Known::kPoint && rel.known == Known::kPoint && rel.ref != placed.ref &&
          !placed.has_other) {
        const Vector2d t = DirectionOf(placed.alpha);
        const Vector2d w = group.placement * rel.point;
        placed.other = placed.point + t * t.dot(w - placed.point);
        placed.has_other = true;
        placed.other_by = group.id;
      }
      continue;
    }
    Placement placement = Apply(group.placement, rel);
    if (rel.known == Known::kAngle) {
      // No comparison pins its line yet: the line as seen when the group was made, from the pose
      // then (§II.A end: "transformed using current position"). In the first group that is one
      // sighting: it is turned about the middle of what was seen to the orientation the group's
      // comparisons give it (§II.C, averaged over their intervals). As one sighting has it, a
      // hallway wall's far piece fitted a fraction of a degree off in the start pose's view (a
      // few of a jamb's points taken with it) keeps that orientation, and the pose turns with
      // it over the next metres. A later group's line fuses the sightings from fixed poses
      // (LineWhenMade), which fix its orientation better than comparisons that do not even pin
      // its line: turned to those, a wall can go more than a degree off, and the next group,
      // placed through it, carries that into its room's walls.
      const double alpha = placement.alpha;
      placement = PlacementOf(LineWhenMade(in, group, id, options), -1);
      if (group.id == 0) placement.alpha = alpha;
    }
    world.global[id] = placement;
    world.chained_alpha[id] = placement.alpha;
    world.placed_by[id] = group.id;
  }
}

void BuildGlobalMap(const GlobalMapInputs& in, size_t from, const MapperOptions& options,
                    Grouping& grouping, WorldMap& world) {
  // Forget what the re-placed groups placed.
  std::set<size_t> earlier;  // groups before `from` that share a plane a re-placed group placed
  for (auto it = world.placed_by.begin(); it != world.placed_by.end();) {
    if (static_cast<size_t>(it->second) >= from) {
      if (const RltPlane* plane = in.store.Plane(it->first)) {
        for (int64_t g : plane->groups) {
          if (static_cast<size_t>(g) < from) earlier.insert(static_cast<size_t>(g));
        }
      }
      world.global.erase(it->first);
      it = world.placed_by.erase(it);
    } else {
      ++it;
    }
  }
  for (auto& [id, placed] : world.global) {
    if (placed.has_other && static_cast<size_t>(placed.other_by) >= from) placed.has_other = false;
  }
  // A plane an earlier group placed and a re-placed one took over (it knew more) goes back to
  // the earlier group's placement: otherwise the re-placed group lost that link and was placed
  // without it (§II.D chains groups through shared planes), from its members' first sightings
  // when it had no other (a door jamb's group turned 3.7 degrees in one iteration).
  for (size_t g : earlier) PlaceMembers(in, grouping.groups[g], options, world);
  // Those go back with their chained orientations: they are refined in this pass as well.
  const size_t refined_from = earlier.empty() ? from : std::min(from, *earlier.begin());
  const Pose2 start{options.start_pose.x, options.start_pose.y, options.start_pose.yaw};
  for (size_t g = from; g < grouping.groups.size(); ++g) {
    Group& group = grouping.groups[g];
    if (group.dirty) {
      group.relative =
          BuildRelativeMap(group, {in.store, in.comparisons, world}, options.comparison);
      group.dirty = false;
    }
    // Through its links as every comparison between mapped walls turns them, as localisation
    // sees them, not as the groups re-placed just before chained them: a group that places a
    // wall from a static edge metres along it from where an earlier group put the wall's line
    // turns the line about that edge, and the chained orientation (through a door's pieces, a
    // fraction of a degree from the refined one) moves a room's side walls and the pose
    // centimetres across the room in one iteration. Refining turns only the walls placed in
    // this pass: without a link among them it would change nothing.
    bool link_replaced = false;
    for (const auto& [id, rel] : group.relative.members) {
      const auto by = world.placed_by.find(id);
      link_replaced |=
          by != world.placed_by.end() && static_cast<size_t>(by->second) >= refined_from;
    }
    if (link_replaced)
      RefineGlobalOrientations(in, grouping, refined_from, options.global_map, world);
    std::vector<Link> links;
    for (const auto& [id, rel] : group.relative.members) {
      auto it = world.global.find(id);
      if (it != world.global.end()) links.push_back({rel, it->second, in.store.Plane(id)});
    }
    // Prior: the basis as seen when the group was made, from the pose then. It only decides
    // directions the links leave open. The basis may change as evidence grows, so the
    // sighting is kept, not the frame.
    Prior prior;
    prior.pose = start;
    if (in.store.Plane(group.relative.basis) != nullptr) {
      prior = PriorWithMemberLines(in, group, options);
    }
    if (links.empty()) {
      // §II.D "the first grouping can be placed on the global map by comparing the relative
      // map coordinates of each rltplane to its first observation".
      // Only observations made from the start pose itself when there are any.
      bool any_at_start = false;
      for (const auto& [id, rel] : group.relative.members) {
        any_at_start |= in.store.Plane(id)->FirstSeen() == in.first_iteration;
      }
      // Each plane's first sighting is kept with the plane: its observations may be gone.
      for (const auto& [id, rel] : group.relative.members) {
        const RltPlane* plane = in.store.Plane(id);
        if (any_at_start && plane->FirstSeen() != in.first_iteration) continue;
        const Observation& first = plane->Observations().front();
        const SeenWall seen = plane->first_seen.valid
                                  ? plane->first_seen
                                  : SeenFrom(first, PoseAt(in, first.iteration, options));
        // Its end too where the sighting shows it, but not where the samples along the wall
        // landed too far apart there (CoarselySampled): seen metres off at a grazing angle, the
        // ends of a side wall's two pieces beside a door recess are sampled decimetres apart and
        // lie centimetres short; the first group, placed between the two, puts them short, and
        // the poses that take them stay off along the hallway for the rest of the run.
        // Its line is taken then, and the prior's ends, each as seen most finely, place it along.
        const int ref = rel.known == Known::kPoint &&
                                FirstSightingShowsEnd(in.trajectory, *plane, seen, rel.ref,
                                                      options.global_map.first_end_agreement) &&
                                !CoarselySampled(in, seen, rel.ref, options)
                            ? rel.ref
                            : -1;
        links.push_back({rel, PlacementOf(seen, ref), plane,
                         SightingOrientationWeight(*plane, seen.iteration)});
      }
    }
    group.placement = Solve(links, prior, options);
    group.chained = group.placement;
    group.has_chained = true;
    PlaceMembers(in, group, options, world);
    group.loop_evidence = GroupLoopEvidence(in.store, grouping, g, options.grouping.recent_groups);
  }
  // Soft-linked groups: when a loop closes (or a closing tie learns more), the group placements
  // are solved together over the graph of ties and every group re-places its members.
  size_t refine_from = refined_from;
  int evidence = 0;
  for (const Group& group : grouping.groups) evidence += group.loop_evidence;
  evidence += world.pose_ties_made;
  if (options.graph.enabled && evidence > world.loop_evidence) {
    world.loop_evidence = evidence;
    const PoseGraphResult solved = OptimiseGroupPlacements(in, world, options, grouping);
    ++world.graph_solves;
    if (solved.cost_after < solved.cost_before) {
      world.global.clear();
      world.placed_by.clear();
      for (Group& group : grouping.groups) PlaceMembers(in, group, options, world);
      refine_from = 0;
    }
  }
  RefineGlobalOrientations(in, grouping, refine_from, options.global_map, world);
  world.changed = true;
}

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
