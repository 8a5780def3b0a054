#include "global_map/global_map.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "comparison/comparison.hpp"
#include "global_map/global_orientations.hpp"
#include "global_map/group_placement.hpp"
#include "global_map/group_prior.hpp"
#include "global_map/pose_graph.hpp"
#include "global_map/relative_map.hpp"
#include "localisation/pose_solver.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;
using geometry::Pose2;

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
    // Its members known by a point as its last build placed them, before the relative map is
    // built again: the prior's last fallback reads only those (group_prior.hpp).
    std::map<int64_t, Placement> previous;
    if (group.has_chained) {
      for (const auto& [id, rel] : group.relative.members) {
        if (rel.known == Known::kPoint) previous.emplace(id, Apply(group.placement, rel));
      }
    }
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
    std::vector<GroupLink> links;
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
      prior = PriorWithMemberLines(in, previous, group, options);
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
    group.placement = SolveGroupPlacement(links, prior, options);
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
    if (solved.consistent || solved.cost_after < solved.cost_before) {
      world.global.clear();
      world.placed_by.clear();
      for (Group& group : grouping.groups) PlaceMembers(in, group, options, world);
      refine_from = 0;
    }
  }
  RefineGlobalOrientations(in, grouping, refine_from, options.global_map, world);
  world.changed = true;
}

}  // namespace relplane::mapper
