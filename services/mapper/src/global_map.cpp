#include "relplane/mapper/global_map.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "relplane/mapper/localisation.hpp"
#include "relplane/mapper/pose_graph.hpp"
#include "relplane/mapper/relative_map.hpp"

namespace relplane::mapper {
namespace {

// rad^-2: the chained orientation as a gauge only, for planes no comparison links to the held
// ones (a comparison's information is 1e2-1e5; 0.01 or 100 here changed no recording's map).
constexpr double kChainedOrientationPrior = 1.0;

using Eigen::Matrix2d;
using Eigen::Vector2d;
using geometry::Pose2;

// m: an end seen from two fixed poses in a row moves less than this if it is the wall's end.
constexpr double kEndStill = 0.05;
// m: the first sighting's end and the latest one agree this well if they are the same end (edge
// noise and the pose's drift since the start).
constexpr double kFirstEndAgreement = 0.2;

Pose2 PoseAt(const MapperState& state, int64_t iteration, const MapperOptions& options) {
  auto it = state.poses.find(iteration);
  if (it != state.poses.end()) return it->second;
  return {options.start_pose.x, options.start_pose.y, options.start_pose.yaw};
}

// The plane's latest observation up to `upto` whose pose is known (its first when `first`).
const Observation& ObservedWithPose(const RltPlane& plane, const MapperState& state, int64_t upto,
                                    bool first) {
  const auto& all = plane.Observations();
  if (first) return all.front();
  for (size_t i = plane.LowerBound(upto + 1); i > 0; --i) {
    if (state.poses.count(all[i - 1].iteration)) return all[i - 1];
  }
  return all.front();
}

// Member `id` of group `g` as seen when the group was made (for the first group, as first
// seen), kept in the group: the group can be placed again once the observation is dropped.
// Kept only once the pose of the group's first iteration is known: a group is built before its
// iteration is localised, and until then the latest sighting with a known pose is an older,
// worse one (keeping it took noise-free office from 9 mm ATE to 30 mm).
SeenWall SeenWhenMade(MapperState& state, size_t g, int64_t id, const MapperOptions& options) {
  Group& group = state.groups[g];
  SeenWall& kept = group.seen[id];
  if (kept.valid) return kept;
  const RltPlane& plane = *state.Plane(id);
  if (g == 0 && plane.first_seen.valid) return kept = plane.first_seen;
  const Observation& obs = ObservedWithPose(plane, state, group.created, g == 0);
  const SeenWall seen = SeenFrom(obs, PoseAt(state, obs.iteration, options));
  if (state.poses.count(group.created) != 0) kept = seen;
  return seen;
}

// m: a sighting's middle this far from the line the others agree on is not the same wall (a
// mis-association, or a pose the walls fixed wrongly); the pose error from fixed poses is a few
// centimetres.
constexpr double kLineAgreement = 0.1;
// m: the error of a fixed pose across a wall, added to each sighting's own offset error so that
// the best-fitting sighting does not take all the weight.
constexpr double kPoseNoise = 0.01;

// Member `id` of group `g`, known by its orientation only, as its sightings from poses the walls
// fixed agree on its line, kept in the group. One sighting does not place it (§II.A end): a wall
// seen edge-on through a door, over 0.1 to 0.5 m, is fitted up to 6 degrees off, and its first
// sighting, 1.6 degrees off, left it 1.4 degrees off on the map for good. Its orientation is the
// mean of theirs weighted by how well each fit fixes it (OrientationWeight, as localisation
// weighs them), its line through the mean of their middles weighted by how well each fixes its
// offset. Also the sightings since the group was made: a member that joined later has none
// before (placing a wall's line from a pose is §II.A's "transformed using current position").
// Falls back to the sighting when the group was made when fewer than two agree.
SeenWall LineWhenMade(MapperState& state, size_t g, int64_t id, const MapperOptions& options) {
  Group& group = state.groups[g];
  const RltPlane& plane = *state.Plane(id);
  const int64_t upto = plane.Latest().iteration;
  auto kept = group.seen_line.find(id);
  if (kept != group.seen_line.end() && kept->second.first >= upto) return kept->second.second;
  const SeenWall made = SeenWhenMade(state, g, id, options);
  if (g == 0) return made;  // the first group's walls are as first seen
  const auto& all = plane.Observations();
  struct Sight {
    SeenWall seen;
    double w_angle, w_offset;
  };
  std::vector<Sight> sights;
  for (size_t i = all.size(); i > 0; --i) {
    const Observation& obs = all[i - 1];
    if (state.fixed_poses.count(obs.iteration) == 0) continue;
    const auto pose = state.poses.find(obs.iteration);
    if (pose == state.poses.end()) continue;
    const double offset_var = obs.support > 0 ? obs.rms * obs.rms / obs.support : 0.0;
    sights.push_back({SeenFrom(obs, pose->second), OrientationWeight(obs),
                      1.0 / (offset_var + kPoseNoise * kPoseNoise)});
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
      use[k] = std::abs(n.dot(mid - fused.edge[0])) <= kLineAgreement;
    }
    if (!fuse(use, &fused)) fused = made;
  }
  // Kept once the group's iteration is localised, as SeenWhenMade: the poses before it may not
  // all be known yet.
  if (state.poses.count(group.created) != 0) group.seen_line[id] = {upto, fused};
  return fused;
}

// Member `id` of group `g` as last seen before the group was made from a pose the walls fixed
// in every direction, kept in the group (invalid when there is none). Poses from the group's
// first iteration on were solved against its own placement, and one the motion model carried
// (§II.E) stood still along a direction the walls left open while the sensor moved on.
const SeenWall& SeenFromFixedPose(MapperState& state, size_t g, int64_t id) {
  Group& group = state.groups[g];
  auto [kept, inserted] = group.seen_fixed.try_emplace(id);
  if (!inserted) return kept->second;
  const RltPlane& plane = *state.Plane(id);
  const auto& all = plane.Observations();
  SeenWall& latest = kept->second;
  for (size_t i = plane.LowerBound(group.created); i > 0; --i) {
    const Observation& obs = all[i - 1];
    if (state.fixed_poses.count(obs.iteration) == 0) continue;
    const SeenWall seen = SeenFrom(obs, state.poses.at(obs.iteration));
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
                      std::abs(t.dot(latest.edge[e] - seen.edge[e])) > kEndStill;
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
bool ShowsEnd(const MapperState& state, const RltPlane& plane, const SeenWall& seen, int ref,
              int64_t before) {
  if (ref < 0 || seen.cut[ref]) return false;
  const auto& all = plane.Observations();
  const Vector2d t = DirectionOf(seen.alpha);
  std::vector<double> along;  // the end's offset from the sighting's, along the wall
  for (size_t i = plane.LowerBound(before); i > 0; --i) {
    const Observation& obs = all[i - 1];
    const auto pose = state.poses.find(obs.iteration);
    if (obs.cut[ref] || obs.iteration == seen.iteration || pose == state.poses.end() ||
        state.fixed_poses.count(obs.iteration) == 0) {
      continue;
    }
    along.push_back(t.dot(pose->second * obs.edge[ref] - seen.edge[ref]));
  }
  if (along.empty()) return true;  // nothing seen from a fixed pose contradicts it
  std::sort(along.begin(), along.end());
  const size_t n = along.size();
  const double median = n % 2 == 1 ? along[n / 2] : 0.5 * (along[n / 2 - 1] + along[n / 2]);
  return std::abs(median) <= kFirstEndAgreement;
}

// ShowsEnd for a member of group `g`, judged once: the sightings before the group was made do
// not change.
bool MemberShowsEnd(MapperState& state, size_t g, int64_t id, const SeenWall& seen, int ref) {
  Group& group = state.groups[g];
  const auto key = std::make_tuple(id, ref, seen.iteration);
  auto it = group.shows_end.find(key);
  if (it == group.shows_end.end()) {
    it = group.shows_end.emplace(key, ShowsEnd(state, *state.Plane(id), seen, ref, group.created))
             .first;
  }
  return it->second;
}

// Prior for group `g`: a member's reference end as seen around when the group was made, put
// back through its place in the relative map. First choice: the latest sighting of each such end
// before the group was made, from a pose the walls fixed. A pose the motion model carried
// stood still along the hallway while the sensor moved on, and every group placed from it kept
// that lag on the map (a hallway with doors lost 0.5 m at each stretch between door frames).
// Only where the earlier such sightings of that end put it (ShowsEnd, §II.C: a wall end stands
// still): an end where the sensor's range ends creeps along with the sensor, less than kEndStill
// an iteration, so the sighting before agrees with it (a group on loop_other_sensor was put
// 1.7 m along its hallway).
// The position is the mean over those ends (the heading the latest one's): one end seen metres
// away is centimetres off, and which end it was changed with the basis chosen afresh at every
// build (a new group's side walls moved 2.5 cm across the room from one iteration to the next).
// Else the basis as seen when the group was made, from a pose the walls fixed, unless the view
// cut its reference end then (a door frame in front hid it: the edge seen was not the wall end
// the relative map starts from, 0.7 m along the wall on the noisy office) or the fixed poses
// just before did not see that end still; then the latest member whose reference end was in
// view so, at about where the sightings of it from fixed poses put it; then the basis's end as
// the fixed poses have seen it since.
Pose2 PriorPlacement(MapperState& state, size_t g, const MapperOptions& options) {
  const RelativeMap& map = state.groups[g].relative;
  int64_t latest = -1;
  Pose2 prior;
  Vector2d sum = Vector2d::Zero();
  int ends = 0;
  for (const auto& [id, rel] : map.members) {
    if (rel.known != Known::kPoint) continue;
    const SeenWall& seen = SeenFromFixedPose(state, g, id);
    if (!seen.valid || !MemberShowsEnd(state, g, id, seen, rel.ref)) {
      continue;
    }
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
  const SeenWall& basis_fixed = SeenFromFixedPose(state, g, basis);
  if (basis_rel.known == Known::kLine && basis_fixed.valid) {
    return PlacementFromSighting(basis_fixed, basis_rel);
  }
  const SeenWall basis_seen = SeenWhenMade(state, g, basis, options);
  prior = PlacementFromSighting(basis_seen, basis_rel);
  // Nor where the latest sighting from a fixed pose before did not show that end still (cut, or
  // moved since the one before; §II.C: a wall end stands still): an end seen far off at a
  // grazing angle is the last sample on the wall, which creeps along with the sensor and jumps
  // back as the next sample lands (a hallway wall's end beside a door, seen 4 m away, put a group
  // and the door jamb it placed 0.12 m along the wall).
  const bool end_moved = basis_rel.ref >= 0 && basis_fixed.valid && basis_fixed.cut[basis_rel.ref];
  // Nor a sighting from a pose the motion model carried (§II.E: while one partial plane is seen,
  // as when turning in place, the position is not solved): a group made then was placed by the
  // ends it saw, 2 to 5 cm off, and its prior flipped between them and the fixed poses' as its
  // basis changed from one build to the next. A door jamb at a corner went 4.6 cm along the
  // hallway, and with it the hallway's next leg across (noisy doors' worst wall 0.056 m).
  const auto from_fixed = [&](const SeenWall& seen) {
    return state.fixed_poses.count(seen.iteration) != 0;
  };
  if (basis_rel.ref < 0 ||
      (!basis_seen.cut[basis_rel.ref] && !end_moved && from_fixed(basis_seen))) {
    return prior;
  }
  // The latest such sighting: the pose it was made from is the nearest to the group's.
  for (const auto& [id, rel] : map.members) {
    if (id == basis || rel.known != Known::kPoint) continue;
    const SeenWall seen = SeenWhenMade(state, g, id, options);
    if (seen.iteration <= latest || !from_fixed(seen)) continue;
    if (!MemberShowsEnd(state, g, id, seen, rel.ref)) continue;
    // Nor a member whose end the fixed poses just before did not see still, as for the basis
    // (§II.C: a wall end stands still): a far wall's end at a grazing angle is its last sample,
    // which creeps along with the sensor (a hallway wall's end beside a door, seen 3.8 m away,
    // lay 0.12 m short of its corner and put a door jamb's group, and the hallway after it, 0.13 m
    // along the hallway).
    const SeenWall& fixed = SeenFromFixedPose(state, g, id);
    if (fixed.valid && fixed.cut[rel.ref]) continue;
    // Nor one far from where the fixed poses have seen that end since (their median): with none
    // seen before, one sighting is all MemberShowsEnd has, and a partition's edge seen once
    // 0.45 m into the door beside it (its pieces joined over the lintel) put an office's door
    // frame, and every room after it, 0.44 m along the partition.
    const SeenWall since = EndSeenFromFixedPoses(state, *state.Plane(id), rel.ref);
    if (since.valid && std::abs(DirectionOf(seen.alpha).dot(since.edge[rel.ref] -
                                                            seen.edge[rel.ref])) >
                           kFirstEndAgreement) {
      continue;
    }
    latest = seen.iteration;
    prior = PlacementFromSighting(seen, rel);
  }
  if (latest >= 0) return prior;
  // No member showed its end around when the group was made (§II.D): the basis's sighting then
  // says nothing along its wall (a side wall first seen where the 6 m range cut it, 1.6 m short of
  // its corner, put a group and every pose after it 1.56 m off). Its end as the fixed poses
  // have seen it since, when they have.
  const SeenWall since = EndSeenFromFixedPoses(state, *state.Plane(basis), basis_rel.ref);
  return since.valid ? PlacementFromSighting(since, basis_rel) : prior;
}

// A group's prior (§II.D): a placement, and the basis's line as seen around when the group was
// made (when the basis is known by more than its orientation), with the basis's place in the
// relative map.
struct Prior {
  Pose2 pose;
  bool has_line = false;
  Vector2d seen_point = Vector2d::Zero();  // on the basis's line as seen, in the world
  Placement basis;
};

// PriorPlacement, with the basis's line as seen to decide the direction across the basis. A
// wall's line is fitted to all its points, while an end is where the sensor's last ray met the
// wall, short of it by up to the rays' spacing along the wall, which grows as they graze it
// (§II.C). PriorPlacement's placement comes from one reference end, so across the basis it
// carried that end's sampling error, or its sighting's heading error times the end's distance
// from the basis: a pilaster's group on loop_other_sensor was put 4 cm, then 8 cm, along the
// hallway, where the pilaster's face, seen square on, put it within 2 mm.
Prior PriorWithBasisLine(MapperState& state, size_t g, const MapperOptions& options) {
  Prior prior;
  prior.pose = PriorPlacement(state, g, options);
  const RelativeMap& map = state.groups[g].relative;
  const Placement& basis = map.members.at(map.basis);
  if (basis.known == Known::kAngle) return prior;
  // As PriorPlacement takes a line: from a fixed pose before the group was made where there is
  // one (§II.E: the motion model's poses lag along open directions).
  const SeenWall& fixed = SeenFromFixedPose(state, g, map.basis);
  const SeenWall seen = fixed.valid ? fixed : SeenWhenMade(state, g, map.basis, options);
  prior.has_line = true;
  prior.seen_point = 0.5 * (seen.edge[0] + seen.edge[1]);
  prior.basis = basis;
  return prior;
}

// Does the plane's first sighting show the end `ref` its relative map starts from? Only if the
// latest uncut sighting of that end from a known pose lies where the first one did. A wall seen
// whole across a door from the start pose (its edges where the view cut it, before the view was
// learnt) is later known by the door-side end of its piece: that end lay 2.6 m along the wall
// from the first sighting's, and the first group was placed 2.6 m off (an unseen office, 70
// degree sensor).
bool FirstSightingShowsEnd(const MapperState& state, const RltPlane& plane, const SeenWall& first,
                           int ref) {
  if (ref < 0 || first.cut[ref]) return false;
  const auto& all = plane.Observations();
  const Vector2d t = DirectionOf(first.alpha);
  for (size_t i = all.size(); i > 0; --i) {
    const Observation& obs = all[i - 1];
    const auto pose = state.poses.find(obs.iteration);
    if (obs.cut[ref] || pose == state.poses.end()) continue;
    return std::abs(t.dot(pose->second * obs.edge[ref] - first.edge[ref])) <= kFirstEndAgreement;
  }
  return true;  // nothing seen since contradicts it
}

struct Link {
  Placement relative;
  Placement global;
  const RltPlane* plane;
};

// Least squares for world <- group: rotation from the mean orientation difference, translation
// from the links' lines (1 equation each) and shared static edges (1 more along the wall).
Pose2 Solve(const std::vector<Link>& links, const Prior& prior_in, double prior_weight) {
  const Pose2& prior = prior_in.pose;
  double s = 0.0, c = 0.0;
  for (const Link& l : links) {
    // Weighted by how well each wall's fit fixes its orientation, as in localisation: a door
    // jamb must not turn a group of walls metres long.
    const double w = OrientationWeight(*l.plane);
    const double d = l.global.alpha - l.relative.alpha;
    s += w * std::sin(d), c += w * std::cos(d);
  }
  const double yaw = links.empty() ? prior.yaw : std::atan2(s, c);
  const Matrix2d rot = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  Matrix2d a = Matrix2d::Zero();
  Vector2d b = Vector2d::Zero();
  for (const Link& l : links) {
    if (l.relative.known == Known::kAngle || l.global.known == Known::kAngle) continue;
    const Vector2d n = NormalOf(l.global.alpha);
    a += n * n.transpose();
    b += n * n.dot(l.global.point - rot * l.relative.point);
  }
  // Lines are exact whatever the edges do; static edges are added only where the lines leave
  // a direction open (parallel walls), since an edge taken for static may not quite be.
  Eigen::SelfAdjointEigenSolver<Matrix2d> eig(a);
  const bool lines_suffice = eig.eigenvalues()(0) >= 0.5;
  for (const Link& l : links) {
    if (lines_suffice) break;
    if (l.relative.known == Known::kAngle || l.global.known == Known::kAngle) continue;
    for (int e = 0; e < 2; ++e) {
      Vector2d rel_point, global_point;
      if (!EdgePoint(*l.plane, l.global, e, &global_point) ||
          !EdgePoint(*l.plane, l.relative, e, &rel_point)) {
        continue;
      }
      const Vector2d t = DirectionOf(l.global.alpha);
      a += t * t.transpose();
      b += t * t.dot(global_point - rot * rel_point);
      break;
    }
  }
  // The prior only decides a direction the links leave open; across the basis, its line as seen
  // with the heading the links give.
  Vector2d prior_t = prior.Translation();
  if (prior_in.has_line) {
    const Vector2d n = NormalOf(yaw + prior_in.basis.alpha);
    prior_t += n * n.dot(prior_in.seen_point - prior_t - rot * prior_in.basis.point);
  }
  const Vector2d t = SolveWithPrior(a, b, prior_t, prior_weight, 0.5);
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

SeenWall EndSeenFromFixedPoses(const MapperState& state, const RltPlane& plane, int ref) {
  SeenWall latest;
  if (ref < 0) return latest;
  std::vector<double> along;  // each sighting's end, along the wall from the latest one's
  const auto& all = plane.Observations();
  for (size_t i = all.size(); i > 0; --i) {
    const Observation& obs = all[i - 1];
    const auto pose = state.poses.find(obs.iteration);
    if (obs.cut[ref] || pose == state.poses.end() || state.fixed_poses.count(obs.iteration) == 0) {
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

void WallEnds(const MapperState& state, const RltPlane& plane, const Placement& placed,
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
    auto pose = state.poses.find(last.iteration);
    if (pose != state.poses.end() || plane.latest_pose_known) {
      const Pose2& from = pose != state.poses.end() ? pose->second : plane.latest_pose;
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
void PlaceMembers(MapperState& state, size_t g, const MapperOptions& options) {
  Group& group = state.groups[g];
  for (const auto& [id, rel] : group.relative.members) {
    // Kept now, while the observation is there, for when this group places it.
    if (rel.known == Known::kAngle) LineWhenMade(state, g, id, options);
    auto it = state.global.find(id);
    // Hard chaining: the first group to place a plane wins, unless a later one knows more.
    // A later group that found the plane's other edge static adds that end to the map.
    if (it != state.global.end() && it->second.known >= rel.known) {
      Placement& placed = it->second;
      if (placed.known == Known::kPoint && rel.known == Known::kPoint && rel.ref != placed.ref &&
          !placed.has_other) {
        const Vector2d t = DirectionOf(placed.alpha);
        const Vector2d w = group.placement * rel.point;
        placed.other = placed.point + t * t.dot(w - placed.point);
        placed.has_other = true;
        placed.other_by = static_cast<int64_t>(g);
      }
      continue;
    }
    Placement world = Apply(group.placement, rel);
    if (rel.known == Known::kAngle) {
      // No comparison pins it yet: its line as seen when the group was made, from the pose
      // then (§II.A end: "transformed using current position").
      world = PlacementOf(LineWhenMade(state, g, id, options), -1);
    }
    state.global[id] = world;
    state.chained_alpha[id] = world.alpha;
    state.placed_by[id] = static_cast<int64_t>(g);
  }
}

void BuildGlobalMap(MapperState& state, size_t from, const MapperOptions& options) {
  // Forget what the re-placed groups placed.
  std::set<size_t> earlier;  // groups before `from` that share a plane a re-placed group placed
  for (auto it = state.placed_by.begin(); it != state.placed_by.end();) {
    if (static_cast<size_t>(it->second) >= from) {
      if (const RltPlane* plane = state.Plane(it->first)) {
        for (int64_t g : plane->groups) {
          if (static_cast<size_t>(g) < from) earlier.insert(static_cast<size_t>(g));
        }
      }
      state.global.erase(it->first);
      it = state.placed_by.erase(it);
    } else {
      ++it;
    }
  }
  for (auto& [id, placed] : state.global) {
    if (placed.has_other && static_cast<size_t>(placed.other_by) >= from) placed.has_other = false;
  }
  // A plane an earlier group placed and a re-placed one took over (it knew more) goes back to
  // the earlier group's placement: otherwise the re-placed group lost that link and was placed
  // without it (§II.D chains groups through shared planes), from its members' first sightings
  // when it had no other (a door jamb's group turned 3.7 degrees in one iteration).
  for (size_t g : earlier) PlaceMembers(state, g, options);
  const Pose2 start{options.start_pose.x, options.start_pose.y, options.start_pose.yaw};
  for (size_t g = from; g < state.groups.size(); ++g) {
    Group& group = state.groups[g];
    if (group.dirty) {
      group.relative = BuildRelativeMap(group, state);
      group.dirty = false;
    }
    std::vector<Link> links;
    for (const auto& [id, rel] : group.relative.members) {
      auto it = state.global.find(id);
      if (it != state.global.end()) links.push_back({rel, it->second, state.Plane(id)});
    }
    // Prior: the basis as seen when the group was made, from the pose then. It only decides
    // directions the links leave open. The basis may change as evidence grows, so the
    // sighting is kept, not the frame.
    Prior prior;
    prior.pose = start;
    if (state.Plane(group.relative.basis) != nullptr) prior = PriorWithBasisLine(state, g, options);
    if (links.empty()) {
      // §II.D "the first grouping can be placed on the global map by comparing the relative
      // map coordinates of each rltplane to its first observation".
      // Only observations made from the start pose itself when there are any.
      bool any_at_start = false;
      for (const auto& [id, rel] : group.relative.members) {
        any_at_start |= state.Plane(id)->FirstSeen() == state.first_iteration;
      }
      // Each plane's first sighting is kept with the plane: its observations may be gone.
      for (const auto& [id, rel] : group.relative.members) {
        const RltPlane* plane = state.Plane(id);
        if (any_at_start && plane->FirstSeen() != state.first_iteration) continue;
        const Observation& first = plane->Observations().front();
        const SeenWall seen = plane->first_seen.valid
                                  ? plane->first_seen
                                  : SeenFrom(first, PoseAt(state, first.iteration, options));
        const int ref =
            rel.known == Known::kPoint && FirstSightingShowsEnd(state, *plane, seen, rel.ref)
                ? rel.ref
                : -1;
        links.push_back({rel, PlacementOf(seen, ref), plane});
      }
    }
    group.placement = Solve(links, prior, options.localisation.prior_weight);
    group.chained = group.placement;
    group.has_chained = true;
    PlaceMembers(state, g, options);
    group.loop_evidence = GroupLoopEvidence(state, g, options.grouping.recent_groups);
  }
  // Soft-linked groups: when a loop closes (or a closing tie learns more), the group placements
  // are solved together over the graph of ties and every group re-places its members.
  size_t refine_from = from;
  int evidence = 0;
  for (const Group& group : state.groups) evidence += group.loop_evidence;
  if (options.graph.enabled && evidence > state.loop_evidence) {
    state.loop_evidence = evidence;
    const PoseGraphResult solved = OptimiseGroupPlacements(state, options.graph);
    ++state.graph_solves;
    if (solved.cost_after < solved.cost_before) {
      state.global.clear();
      state.placed_by.clear();
      for (size_t g = 0; g < state.groups.size(); ++g) PlaceMembers(state, g, options);
      refine_from = 0;
    }
  }
  RefineGlobalOrientations(state, refine_from);
  state.map_changed = true;
}

void RefineGlobalOrientations(MapperState& state, size_t from) {
  // Least squares on the corrections from the chained orientations, as RefineOrientations does
  // within a group, over every comparison between two planes on the global map; the first
  // group's planes are held (§II.D: it is placed from the start pose). Hard chaining (§II.D)
  // gives a wall its orientation from the one group that placed it, through that group's
  // comparisons only. A group made at a door holds the walls of the next room and, of the room
  // it leaves, only the short pieces beside the door, whose fits are off by 1.2-1.5 degrees
  // towards the door, mirrored on its two sides (a piece takes some of the jamb's points): where
  // it holds more pieces of one side (both pieces of the wall and one jamb, the other jamb in the
  // group before), the next room's walls came out 0.33 degrees off, and every later group and
  // pose with them (an unseen office: two walls 6 cm off). The other side's comparisons with
  // those walls were there, in other groups, and balance them: 0.09 degrees, the walls within
  // 4 cm. Anchored at the chained values rather than at the last solution, so solving again
  // after every placement does not walk the orientations away (as pose_graph.cpp's priors).
  // The planes placed before `from` were not re-placed: they are held as last solved.
  std::vector<int64_t> ids;
  std::map<int64_t, int> index;
  for (const auto& [id, g] : state.placed_by) {
    if (g == 0 || static_cast<size_t>(g) < from || !state.chained_alpha.count(id)) continue;
    index[id] = static_cast<int>(ids.size());
    ids.push_back(id);
  }
  const int n = static_cast<int>(ids.size());
  if (n == 0) return;
  // A solved plane from its chained orientation, a held one as it stands.
  auto value = [&](int64_t id) {
    const auto it = index.count(id) ? state.chained_alpha.find(id) : state.chained_alpha.end();
    return it != state.chained_alpha.end() ? it->second : state.global.at(id).alpha;
  };
  // Sparse: a plane is compared only with the members of its groups (§II.C).
  std::set<PairKey> pairs;
  for (int64_t id : ids) {
    for (int64_t g : state.Plane(id)->groups) {
      for (int64_t other : state.groups[g].members) {
        if (other != id) pairs.insert(KeyOf(id, other));
      }
    }
  }
  std::vector<Eigen::Triplet<double>> a;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  for (const PairKey& key : pairs) {
    const Comparison* cmp = state.FindComparison(key.first, key.second);
    if (cmp == nullptr || !state.global.count(key.first) || !state.global.count(key.second)) {
      continue;
    }
    const double w = cmp->PieceInformation();
    if (w <= 0.0) continue;
    const auto ix = index.find(key.first), iy = index.find(key.second);
    const int x = ix == index.end() ? -1 : ix->second, y = iy == index.end() ? -1 : iy->second;
    const double r =
        geometry::WrapAngle(value(key.second) - value(key.first) - cmp->PieceAlpha(key.first));
    if (y >= 0) a.emplace_back(y, y, w), b(y) -= w * r;
    if (x >= 0) a.emplace_back(x, x, w), b(x) += w * r;
    if (x >= 0 && y >= 0) a.emplace_back(x, y, -w), a.emplace_back(y, x, -w);
  }
  // A weak prior at the chained value: the gauge of planes no comparison ties to the held ones.
  for (int k = 0; k < n; ++k) a.emplace_back(k, k, kChainedOrientationPrior);
  Eigen::SparseMatrix<double> h(n, n);
  h.setFromTriplets(a.begin(), a.end());  // duplicates are summed
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(h);
  if (solver.info() != Eigen::Success) return;
  const Eigen::VectorXd dx = solver.solve(b);
  if (!dx.allFinite()) return;
  for (int k = 0; k < n; ++k) {
    state.global.at(ids[k]).alpha = geometry::WrapAngle(value(ids[k]) + dx(k));
  }
}

}  // namespace relplane::mapper
