#include "global_map/group_prior.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "eigen_solver_2d.hpp"
#include "global_map/global_map.hpp"
#include "localisation/pose_solver.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;
using geometry::Pose2;

// m: samples this far apart along a wall put its end off by more than the end's own noise
// (LocalisationOptions::edge_noise, 2 sigma) could.
double CoarseSpacing(const MapperOptions& options) { return 2.0 * options.localisation.edge_noise; }

}  // namespace

Pose2 PoseAt(const GlobalMapInputs& in, int64_t iteration, const MapperOptions& options) {
  auto it = in.trajectory.poses.find(iteration);
  if (it != in.trajectory.poses.end()) return it->second;
  return {options.start_pose.x, options.start_pose.y, options.start_pose.yaw};
}

namespace {

// The plane's latest observation up to `upto` whose pose is known (its first when `first`).
const Observation& ObservedWithPose(const RltPlane& plane, const GlobalMapInputs& in, int64_t upto,
                                    bool first) {
  const auto& all = plane.Observations();
  if (first) return all.front();
  for (size_t i = plane.LowerBound(upto + 1); i > 0; --i) {
    if (in.trajectory.poses.count(all[i - 1].iteration)) return all[i - 1];
  }
  return all.front();
}

// Member `id` of `group` as seen when the group was made (for the first group, as first
// seen), kept in the group: the group can be placed again once the observation is dropped.
// Kept only once the pose of the group's first iteration is known: a group is built before its
// iteration is localised, and until then the latest sighting with a known pose is an older,
// worse one, from which the group, once it kept it, would be placed at every later build.
SeenWall SeenWhenMade(const GlobalMapInputs& in, Group& group, int64_t id,
                      const MapperOptions& options) {
  SeenWall& kept = group.seen[id];
  if (kept.valid) return kept;
  const RltPlane& plane = *in.store.Plane(id);
  if (group.id == 0 && plane.first_seen.valid) return kept = plane.first_seen;
  const Observation& obs = ObservedWithPose(plane, in, group.created, group.id == 0);
  const SeenWall seen = SeenFrom(obs, PoseAt(in, obs.iteration, options));
  if (in.trajectory.poses.count(group.created) != 0) kept = seen;
  return seen;
}

}  // namespace

SeenWall LineWhenMade(const GlobalMapInputs& in, Group& group, int64_t id,
                      const MapperOptions& options) {
  const RltPlane& plane = *in.store.Plane(id);
  const int64_t upto = plane.Latest().iteration;
  auto kept = group.seen_line.find(id);
  if (kept != group.seen_line.end() && kept->second.first >= upto) return kept->second.second;
  const SeenWall made = SeenWhenMade(in, group, id, options);
  if (group.id == 0) return made;  // the first group's walls are as first seen
  const auto& all = plane.Observations();
  struct Sight {
    SeenWall seen;
    double w_angle, w_offset;
  };
  std::vector<Sight> sights;
  for (size_t i = all.size(); i > 0; --i) {
    const Observation& obs = all[i - 1];
    if (in.trajectory.fixed.count(obs.iteration) == 0) continue;
    const auto pose = in.trajectory.poses.find(obs.iteration);
    if (pose == in.trajectory.poses.end()) continue;
    const double offset_var = obs.support > 0 ? obs.rms * obs.rms / obs.support : 0.0;
    sights.push_back(
        {SeenFrom(obs, pose->second), OrientationWeight(obs, options.fit),
         1.0 / (offset_var + options.global_map.pose_noise * options.global_map.pose_noise)});
  }
  const auto fuse = [&](const std::vector<bool>& use, SeenWall* out) {
    double s = 0.0, c = 0.0, wsum = 0.0;
    Vector2d mid = Vector2d::Zero();
    int n = 0;
    const SeenWall* latest = nullptr;
    for (size_t k = 0; k < sights.size(); ++k) {
      if (!use[k]) continue;
      if (latest == nullptr) latest = &sights[k].seen;
      const double d = geometry::WrapAngle(sights[k].seen.alpha - latest->alpha);
      s += sights[k].w_angle * std::sin(d), c += sights[k].w_angle * std::cos(d);
      mid += sights[k].w_offset * 0.5 * (sights[k].seen.edge[0] + sights[k].seen.edge[1]);
      wsum += sights[k].w_offset;
      ++n;
    }
    if (n < 2) return false;
    *out = *latest;  // its extent along the wall
    out->alpha = geometry::WrapAngle(latest->alpha + std::atan2(s, c));
    const Vector2d p = mid / wsum, t = DirectionOf(out->alpha);
    for (int e = 0; e < 2; ++e) out->edge[e] = p + t * t.dot(out->edge[e] - p);
    out->foot = p + t * t.dot(out->foot - p);
    return true;
  };
  SeenWall fused = made;
  std::vector<bool> use(sights.size(), true);
  if (fuse(use, &fused)) {
    const Vector2d n = NormalOf(fused.alpha);
    for (size_t k = 0; k < sights.size(); ++k) {
      const Vector2d mid = 0.5 * (sights[k].seen.edge[0] + sights[k].seen.edge[1]);
      use[k] = std::abs(n.dot(mid - fused.edge[0])) <= options.global_map.line_agreement;
    }
    if (!fuse(use, &fused)) fused = made;
  }
  // Kept once the group's iteration is localised, as SeenWhenMade: the poses before it may not
  // all be known yet.
  if (in.trajectory.poses.count(group.created) != 0) group.seen_line[id] = {upto, fused};
  return fused;
}

namespace {

// Member `id` of `group` as last seen before the group was made from a pose the walls fixed
// in every direction, kept in the group (invalid when there is none). Poses from the group's
// first iteration on were solved against its own placement, and one the motion model carried
// (§II.E) stood still along a direction the walls left open while the sensor moved on.
const SeenWall& SeenFromFixedPose(const GlobalMapInputs& in, Group& group, int64_t id,
                                  const GlobalMapOptions& o) {
  auto [kept, inserted] = group.seen_fixed.try_emplace(id);
  if (!inserted) return kept->second;
  const RltPlane& plane = *in.store.Plane(id);
  const auto& all = plane.Observations();
  SeenWall& latest = kept->second;
  for (size_t i = plane.LowerBound(group.created); i > 0; --i) {
    const Observation& obs = all[i - 1];
    if (in.trajectory.fixed.count(obs.iteration) == 0) continue;
    const SeenWall seen = SeenFrom(obs, in.trajectory.poses.at(obs.iteration));
    if (!latest.valid) {
      latest = seen;
      continue;
    }
    // A wall end stands still (§II.C): an end the sighting before did not see at the same
    // place was where a nearer plane hid the wall, however the view judged it (a far wall's end
    // beside a door jamb, 0.45 m short of the corner, put a group 0.24 m along its wall).
    const Eigen::Vector2d t = DirectionOf(latest.alpha);
    for (int e = 0; e < 2; ++e) {
      latest.cut[e] = latest.cut[e] || seen.cut[e] ||
                      std::abs(t.dot(latest.edge[e] - seen.edge[e])) > o.end_still;
    }
    break;
  }
  return latest;
}

// The group's placement from one member as seen when the group was made: its sighting then
// put back through its place in the relative map.
Pose2 PlacementFromSighting(const SeenWall& seen, const Placement& rel) {
  const double yaw = geometry::WrapAngle(seen.alpha - rel.alpha);
  const Placement p = PlacementOf(seen, rel.ref);
  const Vector2d t = p.point - Eigen::Rotation2Dd(yaw) * rel.point;
  return {t.x(), t.y(), yaw};
}

// Does `seen`, a sighting of `plane`, show the wall's end `ref`? Not where the view cut it, nor
// far from where the sightings of that end from poses the walls fixed before `before` put it
// (their median, so that one outlier among them does not decide): a wall end stands still
// (§II.C), and an end seen elsewhere was a segmenter outlier (a corner's end seen once 0.4 m
// past the corner, from a pose the motion model carried round it, put a group and the whole
// loop after it 0.4 m off).
bool ShowsEnd(const GlobalMapInputs& in, const GlobalMapOptions& o, const RltPlane& plane,
              const SeenWall& seen, int ref, int64_t before) {
  if (ref < 0 || seen.cut[ref]) return false;
  const auto& all = plane.Observations();
  const Vector2d t = DirectionOf(seen.alpha);
  std::vector<double> along;  // the end's offset from the sighting's, along the wall
  for (size_t i = plane.LowerBound(before); i > 0; --i) {
    const Observation& obs = all[i - 1];
    const auto pose = in.trajectory.poses.find(obs.iteration);
    if (obs.cut[ref] || obs.iteration == seen.iteration || pose == in.trajectory.poses.end() ||
        in.trajectory.fixed.count(obs.iteration) == 0) {
      continue;
    }
    along.push_back(t.dot(pose->second * obs.edge[ref] - seen.edge[ref]));
  }
  if (along.empty()) return true;  // nothing seen from a fixed pose contradicts it
  std::sort(along.begin(), along.end());
  const size_t n = along.size();
  const double median = n % 2 == 1 ? along[n / 2] : 0.5 * (along[n / 2 - 1] + along[n / 2]);
  return std::abs(median) <= o.first_end_agreement;
}

// ShowsEnd for a member of `group`, judged once: the sightings before the group was made do
// not change.
bool MemberShowsEnd(const GlobalMapInputs& in, const GlobalMapOptions& o, Group& group, int64_t id,
                    const SeenWall& seen, int ref) {
  const auto key = std::make_tuple(id, ref, seen.iteration);
  auto it = group.shows_end.find(key);
  if (it == group.shows_end.end()) {
    it =
        group.shows_end.emplace(key, ShowsEnd(in, o, *in.store.Plane(id), seen, ref, group.created))
            .first;
  }
  return it->second;
}

// m between the sensor's samples along the wall at end `ref` of `seen`, from the pose it was seen
// from (EdgeSpacing). Nought while the angle between rays is not known.
double SpacingAt(const GlobalMapInputs& in, const SeenWall& seen, int ref) {
  const auto pose = in.trajectory.poses.find(seen.iteration);
  if (pose == in.trajectory.poses.end()) return 0.0;
  const Vector2d r = seen.edge[ref] - pose->second.Translation();
  return EdgeSpacing(in.angular_step, r, std::abs(NormalOf(seen.alpha).dot(r)));
}

// Member `id`'s end `ref` as most finely sampled from a pose the walls fixed, up to now, where it
// stood still since the sighting from a fixed pose before (§II.C: a wall end stands still), and
// that sighting's spacing. The observations are scanned once each, as they come.
const SeenWall& FinestEndSighting(const GlobalMapInputs& in, const GlobalMapOptions& o,
                                  Group& group, int64_t id, int ref, double* spacing) {
  Group::FinestEnd& fine = group.finest_end[{id, ref}];
  const RltPlane& plane = *in.store.Plane(id);
  const auto& all = plane.Observations();
  for (size_t i = plane.LowerBound(fine.scanned + 1); i < all.size(); ++i) {
    const Observation& obs = all[i];
    const auto pose = in.trajectory.poses.find(obs.iteration);
    if (pose == in.trajectory.poses.end()) break;  // this iteration's, not localised yet
    fine.scanned = obs.iteration;
    if (in.trajectory.fixed.count(obs.iteration) == 0) continue;
    const SeenWall seen = SeenFrom(obs, pose->second);
    const SeenWall before = fine.previous;
    fine.previous = seen;
    if (seen.cut[ref] || !before.valid || before.cut[ref] ||
        std::abs(DirectionOf(seen.alpha).dot(seen.edge[ref] - before.edge[ref])) > o.end_still) {
      continue;
    }
    const double s = SpacingAt(in, seen, ref);
    if (!fine.seen.valid || s < fine.spacing) fine.seen = seen, fine.spacing = s;
  }
  *spacing = fine.spacing;
  return fine.seen;
}

// The plane's latest sighting from a known pose whose end `ref` the view did not cut
// (Observation::ViewCut: one too coarsely sampled to place by itself still counts); invalid when
// there is none.
SeenWall LatestUncutSighting(const GlobalMapInputs& in, const RltPlane& plane, int ref) {
  const auto& all = plane.Observations();
  for (size_t i = all.size(); i > 0; --i) {
    const Observation& obs = all[i - 1];
    const auto pose = in.trajectory.poses.find(obs.iteration);
    if (!obs.ViewCut(ref) && pose != in.trajectory.poses.end()) return SeenFrom(obs, pose->second);
  }
  return {};
}

// Prior for `group`: a member's reference end as seen around when the group was made, put
// back through its place in the relative map. First choice: the latest sighting of each such end
// before the group was made, from a pose the walls fixed, or where the fixed poses have seen that
// end more finely sampled since, that sighting. A pose the motion model carried (§II.E) stands
// still along the hallway while the sensor moves on, and every group placed from it keeps that
// lag on the map (in a hallway with doors, half a metre at each stretch between door frames).
// Only where the earlier such sightings of that end put it (ShowsEnd, §II.C: a wall end stands
// still): an end where the sensor's range ends creeps along with the sensor, less than
// `global_map.end_still` an iteration, so the sighting before agrees with it, and a group placed
// from it goes metres along its hallway. The position is the mean over those ends (the heading the
// latest one's): one end seen metres away is centimetres off, and which end it is changes with the
// basis chosen afresh at every build (a new group's walls would move centimetres across the room
// from one iteration to the next). Else the basis as seen when the group was made, from a pose the
// walls fixed, unless the view cut its reference end then (a door frame in front hid it: the edge
// seen was not the wall end the relative map starts from, but decimetres along the wall) or the
// fixed poses just before did not see that end still; then the latest member whose reference end
// was in view so, at about where the sightings of it from fixed poses put it; then the basis's end
// as the fixed poses have seen it since; then, where the view cut the basis's sighting, where the
// group's last build (`previous`) put that end.
Pose2 PriorPlacement(const GlobalMapInputs& in, const std::map<int64_t, Placement>& previous,
                     Group& group, const MapperOptions& options) {
  const RelativeMap& map = group.relative;
  int64_t latest = -1;
  Pose2 prior;
  Vector2d sum = Vector2d::Zero();
  int ends = 0;
  for (const auto& [id, rel] : map.members) {
    if (rel.known != Known::kPoint) continue;
    const SeenWall& made = SeenFromFixedPose(in, group, id, options.global_map);
    if (!made.valid || !MemberShowsEnd(in, options.global_map, group, id, made, rel.ref)) {
      continue;
    }
    // Seen more finely since, from a fixed pose, where it stood still: that sighting. The last
    // sample on a wall lies up to a sample's spacing short of its end, and the spacing grows with
    // the square of the range as the rays graze the wall: a side wall's end beside a door, seen
    // metres down the hallway with samples decimetres apart, puts a group centimetres along the
    // hallway, and the walls it places there, and the poses that come back past them, stay as
    // far off.
    // Only where the sighting then was that coarse (samples further apart than CoarseSpacing),
    // and the later one at most half as coarse: a pose fixed after the group was made may have
    // been fixed by the group itself, so a sighting from it brings the group back to where it
    // is, give or take the pose's error. Taken where the sighting then was already fine, the
    // finest sightings of a wall's end beside a door as the sensor passes it come from poses
    // centimetres off along the hallway; the group follows them, the poses the group, and both
    // drift along it together.
    double fine_spacing = 0.0;
    const SeenWall& fine =
        FinestEndSighting(in, options.global_map, group, id, rel.ref, &fine_spacing);
    const double made_spacing = SpacingAt(in, made, rel.ref);
    const bool finer =
        fine.valid && made_spacing > CoarseSpacing(options) && fine_spacing <= 0.5 * made_spacing;
    const SeenWall& seen = finer ? fine : made;
    const Pose2 p = PlacementFromSighting(seen, rel);
    sum += p.Translation();
    ++ends;
    if (seen.iteration <= latest) continue;
    latest = seen.iteration;
    prior = p;
  }
  if (latest >= 0) {
    const Vector2d mean = sum / ends;
    return {mean.x(), mean.y(), prior.yaw};
  }
  const int64_t basis = map.basis;
  const Placement& basis_rel = map.members.at(basis);
  // A basis known by its line only: its line as last seen from a fixed pose before the group
  // was made, for the same reason (turning in place at a corner, the pose the motion model
  // carried across the wall's line was 2 cm off, and so was the wall).
  const SeenWall& basis_fixed = SeenFromFixedPose(in, group, basis, options.global_map);
  if (basis_rel.known == Known::kLine && basis_fixed.valid) {
    return PlacementFromSighting(basis_fixed, basis_rel);
  }
  const SeenWall basis_seen = SeenWhenMade(in, group, basis, options);
  prior = PlacementFromSighting(basis_seen, basis_rel);
  // Nor where the latest sighting from a fixed pose before did not show that end still (cut, or
  // moved since the one before; §II.C: a wall end stands still): an end seen far off at a
  // grazing angle is the last sample on the wall, which creeps along with the sensor and jumps
  // back as the next sample lands (a hallway wall's end beside a door, seen 4 m away, put a group
  // and the door jamb it placed 0.12 m along the wall).
  const bool end_moved = basis_rel.ref >= 0 && basis_fixed.valid && basis_fixed.cut[basis_rel.ref];
  // Nor a sighting from a pose the motion model carried (§II.E: while one partial plane is seen,
  // as when turning in place, the position is not solved): a group made then is placed by the
  // ends it saw, centimetres off, and its prior flips between them and the fixed poses' as its
  // basis changes from one build to the next; a door jamb at a corner moves along the hallway,
  // and with it the hallway's next leg across.
  const auto from_fixed = [&](const SeenWall& seen) {
    return in.trajectory.fixed.count(seen.iteration) != 0;
  };
  if (basis_rel.ref < 0 ||
      (!basis_seen.cut[basis_rel.ref] && !end_moved && from_fixed(basis_seen))) {
    return prior;
  }
  // The latest such sighting: the pose it was made from is the nearest to the group's.
  for (const auto& [id, rel] : map.members) {
    if (id == basis || rel.known != Known::kPoint) continue;
    const SeenWall seen = SeenWhenMade(in, group, id, options);
    if (seen.iteration <= latest || !from_fixed(seen)) continue;
    if (!MemberShowsEnd(in, options.global_map, group, id, seen, rel.ref)) continue;
    // Nor a member whose end the fixed poses just before did not see still, as for the basis
    // (§II.C: a wall end stands still): a far wall's end at a grazing angle is its last sample,
    // which creeps along with the sensor (a hallway wall's end beside a door, seen 3.8 m away,
    // lay 0.12 m short of its corner and put a door jamb's group, and the hallway after it, 0.13 m
    // along the hallway).
    const SeenWall& fixed = SeenFromFixedPose(in, group, id, options.global_map);
    if (fixed.valid && fixed.cut[rel.ref]) continue;
    // Nor one far from where the fixed poses have seen that end since (their median): with none
    // seen before, one sighting is all MemberShowsEnd has, and a partition's edge seen once
    // 0.45 m into the door beside it (its pieces joined over the lintel) put an office's door
    // frame, and every room after it, 0.44 m along the partition.
    const SeenWall since = EndSeenFromFixedPoses(in.trajectory, *in.store.Plane(id), rel.ref);
    if (since.valid &&
        std::abs(DirectionOf(seen.alpha).dot(since.edge[rel.ref] - seen.edge[rel.ref])) >
            options.global_map.first_end_agreement) {
      continue;
    }
    latest = seen.iteration;
    prior = PlacementFromSighting(seen, rel);
  }
  if (latest >= 0) return prior;
  // No member showed its end around when the group was made (§II.D): the basis's sighting then
  // says nothing along its wall (a side wall first seen where the 6 m range cut it, 1.6 m short of
  // its corner, put a group and every pose after it 1.56 m off). Its end as the fixed poses
  // have seen it since the group was made, when they have. Not from before: the end the group's
  // relative map starts from is the one its members' comparisons saw, and the rltplane's end
  // seen earlier may be another end of the surface (a collinear piece's before a doorway, seen
  // from the start), metres along the wall.
  const SeenWall since =
      EndSeenFromFixedPoses(in.trajectory, *in.store.Plane(basis), basis_rel.ref);
  if (since.valid && since.iteration >= group.created) {
    return PlacementFromSighting(since, basis_rel);
  }
  // Nor since: a sighting whose end the view cut says nothing along its wall, so the group stays
  // where its last build put that end, when it had it (no new evidence, no move).
  const auto placed = previous.find(basis);
  if (basis_seen.cut[basis_rel.ref] && placed != previous.end() &&
      placed->second.known == Known::kPoint && placed->second.ref == basis_rel.ref) {
    const double yaw = geometry::WrapAngle(placed->second.alpha - basis_rel.alpha);
    const Vector2d t = placed->second.point - Eigen::Rotation2Dd(yaw) * basis_rel.point;
    return {t.x(), t.y(), yaw};
  }
  // Nor a last build that placed it: the latest sighting the view did not cut there, from
  // whatever pose it was made (one the motion model or odometry carried, §II.E), its end within
  // a sample's spacing. A cut edge lies anywhere short of the end, so it never places the group
  // along its wall (§II.C: a cut edge is no static edge).
  if (basis_seen.cut[basis_rel.ref]) {
    const SeenWall latest_end = LatestUncutSighting(in, *in.store.Plane(basis), basis_rel.ref);
    if (latest_end.valid) return PlacementFromSighting(latest_end, basis_rel);
  }
  return prior;
}

}  // namespace

bool CoarselySampled(const GlobalMapInputs& in, const SeenWall& seen, int ref,
                     const MapperOptions& options) {
  return SpacingAt(in, seen, ref) > CoarseSpacing(options);
}

Prior PriorWithMemberLines(const GlobalMapInputs& in, const std::map<int64_t, Placement>& previous,
                           Group& group, const MapperOptions& options) {
  Prior prior;
  prior.pose = PriorPlacement(in, previous, group, options);
  const RelativeMap& map = group.relative;
  Eigen::Matrix2d spanned = Eigen::Matrix2d::Zero();
  std::vector<int64_t> late;
  for (const auto& [id, member] : map.members) {
    if (member.known == Known::kAngle) continue;
    // As PriorPlacement takes a line: from a fixed pose before the group was made where there is
    // one (§II.E: the motion model's poses lag along open directions); the basis, which the
    // placement hangs on, as seen when the group was made otherwise.
    const SeenWall& fixed = SeenFromFixedPose(in, group, id, options.global_map);
    if (!fixed.valid && id != map.basis) {
      late.push_back(id);
      continue;
    }
    const SeenWall seen = fixed.valid ? fixed : SeenWhenMade(in, group, id, options);
    prior.lines.push_back(
        {0.5 * (seen.edge[0] + seen.edge[1]), member, in.store.Plane(id)->Length()});
    const Vector2d n = NormalOf(member.alpha);
    spanned += n * n.transpose();
  }
  // Where those lines leave a direction open (a hallway's side walls), the prior's ends decide
  // it, each seen far off at a grazing angle and short by up to a column's spacing. A member seen
  // face-on across that direction but only since the group was made (the hallway's end wall,
  // out of range until then) fixes it better: its line as the fixed poses have seen it, as the
  // map already draws it while the group knows it by its angle only. Without it the group stands
  // centimetres short of the end wall, and when the wall becomes a point of the group's relative
  // map (its corner with the side wall static) the group and the pose jump back in one iteration.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(spanned);
  if (eig.eigenvalues()(0) >= options.localisation.open_information) return prior;
  const Vector2d open = eig.eigenvectors().col(0);
  for (int64_t id : late) {
    const Placement& member = map.members.at(id);
    if (std::abs(NormalOf(member.alpha).dot(open)) < options.global_map.spans_open) continue;
    // Not from poses the motion model carried: they stood still along that open direction.
    const SeenWall seen = LineWhenMade(in, group, id, options);
    if (in.trajectory.fixed.count(seen.iteration) == 0) continue;
    prior.lines.push_back(
        {0.5 * (seen.edge[0] + seen.edge[1]), member, in.store.Plane(id)->Length()});
  }
  return prior;
}

}  // namespace relplane::mapper
