#include "plane_store/registration.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <tuple>

namespace relplane::mapper {
namespace {

// Overlap of [a0, a1] and [b0, b1] as a fraction of the shorter one.
double Overlap(double a0, double a1, double b0, double b1) {
  const double shorter = std::max(std::min(a1 - a0, b1 - b0), 1e-3);
  return std::max(0.0, std::min(a1, b1) - std::max(a0, b0)) / shorter;
}

// Does `piece` lie on `wall`'s line, turned by no more than the plane-equation test allows and
// overlapping it in height? Judged by the distance to the wall's line at the piece's middle,
// not the offsets d: a piece a few degrees off has its d far from the wall's when it lies far
// from the foot of the sensor's normal. Nor at its ends: a fit is known best at its middle, and
// its ends are off the line by its orientation error over half its length (a 1.5 m piece 5
// degrees off has an end 6 cm off the wall's line and its middle on it). Taken for a second
// plane, such a piece turns the walls placed from it (§II.A).
bool OnLineOf(const Observation& piece, const Observation& wall,
              const RegistrationOptions& options) {
  const double angle = std::acos(std::clamp(piece.normal.dot(wall.normal), -1.0, 1.0));
  const Eigen::Vector2d middle = 0.5 * (piece.edge[0] + piece.edge[1]);
  return angle <= options.max_angle &&
         std::abs(wall.normal.dot(middle) + wall.d) <= options.same_surface &&
         Overlap(wall.z_min, wall.z_max, piece.z_min, piece.z_max) >= options.min_overlap;
}

// Does `piece` lie along `wall` (both seen in the same iteration), the latter fitted to more
// points? Of two reports of one surface the one with the wider support is the better fit (a
// short jamb face reported twice, each piece a few degrees off). On the wall's line, and
// either overlapping it along the wall as the bounding box test of §II.A asks of a match, or
// going on past its end only where the view cuts it:
// - a recess's short side wall can be reported as two fits crossing at its middle, a few
//   degrees apart, the lesser one reaching past the wall's end (points of the corner beside
//   it); kept, it becomes a second rltplane, takes the wall's later sightings and is mapped as
//   its duplicate;
// - the segmenter splits the nearest columns of a wall seen at a glancing angle off as a strip
//   a few centimetres long, several degrees off, beside the wall: kept, it is mapped as the
//   wall's duplicate.
// A collinear wall past a corner or a door does not touch it; a piece only touching it past a
// real end (a jamb's corner) is kept: merged, its fit turned the wall.
bool LiesAlong(const Observation& piece, const Observation& wall,
               const RegistrationOptions& options,
               const std::function<bool(const Eigen::Vector2d&)>& at_view_edge) {
  if (piece.support >= wall.support || !OnLineOf(piece, wall, options)) return false;
  const Eigen::Vector2d t = wall.Direction();
  double w0 = t.dot(wall.edge[0]), w1 = t.dot(wall.edge[1]);
  double p0 = t.dot(piece.edge[0]), p1 = t.dot(piece.edge[1]);
  if (w0 > w1) std::swap(w0, w1);
  if (p0 > p1) std::swap(p0, p1);
  if (Overlap(w0, w1, p0, p1) >= options.min_overlap) return true;
  bool touches = false;
  for (int e = 0; e < 2; ++e) {
    const double s = t.dot(piece.edge[e]);
    if (s >= w0 - options.same_surface && s <= w1 + options.same_surface) {
      touches = true;
    } else if (!at_view_edge || !at_view_edge(piece.edge[e])) {
      return false;
    }
  }
  return touches;
}

// Extends `wall` along its line over the part of `piece` past its ends where the view cuts the
// piece, so the sighting reaches as far as the surface was seen (the view then marks that end
// cut, §II.C). A piece's end past a real end is its fit's, not the wall's.
void Absorb(const Observation& piece, Observation* wall,
            const std::function<bool(const Eigen::Vector2d&)>& at_view_edge) {
  const Eigen::Vector2d t = wall->Direction();
  for (const Eigen::Vector2d& p : piece.edge) {
    if (!at_view_edge || !at_view_edge(p)) continue;
    const Eigen::Vector2d on_line = p - (wall->normal.dot(p) + wall->d) * wall->normal;
    if (t.dot(on_line) < t.dot(wall->edge[0])) wall->edge[0] = on_line;
    if (t.dot(on_line) > t.dot(wall->edge[1])) wall->edge[1] = on_line;
  }
}

// Are rltplanes `a` and `b` the same surface: `a`'s latest sighting, moved from the pose it was
// seen from into the one `b`'s latest was seen from, on the line of `b`'s?
bool SameSurface(const PlaneStore& store, const Trajectory& trajectory, int64_t a, int64_t b,
                 const RegistrationOptions& options) {
  const auto pa = store.planes.find(a), pb = store.planes.find(b);
  if (pa == store.planes.end() || pb == store.planes.end()) return false;
  const Observation& la = pa->second.Latest();
  const Observation& lb = pb->second.Latest();
  const auto from = trajectory.poses.find(la.iteration), to = trajectory.poses.find(lb.iteration);
  if (from == trajectory.poses.end() || to == trajectory.poses.end()) return false;
  const geometry::Pose2 motion = to->second.Inverse() * from->second;
  Observation moved = la;
  moved.normal = motion.Rotation() * la.normal;
  moved.edge[0] = motion * la.edge[0];
  moved.edge[1] = motion * la.edge[1];
  moved.d = -moved.normal.dot(moved.edge[0]);
  return OnLineOf(moved, lb, options);
}

// A candidate match: score, observation, rltplane.
using Candidate = std::tuple<double, size_t, int64_t>;

// For each observation a line only (both ends cut by the view) and registered to a rltplane the
// map does not place, another, mapped, rltplane of that surface with more sightings that it
// matched too and no plane took: the wall's older rltplane. The segmenter reports a wall in two
// pieces beside a door in one frame and as one across it in the next; the whole matches the
// rltplanes of both, and the younger, a piece's, may score a hair higher and take it. The wall's
// own rltplane then gets nothing, frame after frame; while the sensor turns on the spot with that
// wall the one long mapped wall in view, the heading is left to short pieces such as a jamb and
// stays off for the rest of the run (§II.D: the pose comes from the mapped walls in view). Both
// rltplanes take the sighting: the younger as before, as the groups were built with it (handed
// to the older alone, the groups change, and a group may be placed from a far corner's end seen
// short), the older to stay in view and place the pose. Not a sighting with an end in view: fed
// to the older too, that end changes the groups the same way; a line only adds no end to either.
// Nor where the one that took it is mapped: the pose has the wall then, and a sighting fed to two
// mapped rltplanes of one surface moves the wall.
std::vector<int64_t> AlsoSeenAs(const std::vector<Observation>& observations,
                                const std::vector<int64_t>& match,
                                const std::vector<Candidate>& candidates,
                                const std::map<int64_t, size_t>& taken_by, const PlaneStore& store,
                                const WorldMap& world, const Trajectory& trajectory,
                                const RegistrationOptions& options) {
  std::vector<int64_t> also(observations.size(), -1);
  std::set<int64_t> also_taken;
  for (const auto& [score, k, id] : candidates) {
    const Observation& obs = observations[k];
    if (match[k] < 0 || also[k] >= 0 || id == match[k] || !obs.cut[0] || !obs.cut[1] ||
        taken_by.count(id) || also_taken.count(id) || world.global.count(id) == 0 ||
        world.global.count(match[k]) != 0) {
      continue;
    }
    if (store.planes.at(id).Count() <= store.planes.at(match[k]).Count()) continue;
    if (!SameSurface(store, trajectory, id, match[k], options)) continue;
    also[k] = id;
    also_taken.insert(id);
  }
  return also;
}

}  // namespace

void DropRepeatedSightings(std::vector<Observation>* observations,
                           const RegistrationOptions& options,
                           const std::function<bool(const Eigen::Vector2d&)>& at_view_edge) {
  std::vector<Observation>& obs = *observations;
  std::vector<bool> drop(obs.size(), false);
  for (size_t k = 0; k < obs.size(); ++k) {
    for (size_t j = 0; j < obs.size() && !drop[k]; ++j) {
      drop[k] = j != k && !drop[j] && LiesAlong(obs[k], obs[j], options, at_view_edge);
      if (drop[k]) Absorb(obs[k], &obs[j], at_view_edge);
    }
  }
  size_t kept = 0;
  for (size_t k = 0; k < obs.size(); ++k) {
    if (!drop[k]) obs[kept++] = std::move(obs[k]);
  }
  obs.resize(kept);
}

double MatchScore(const Observation& latest, const Observation& obs,
                  const RegistrationOptions& options, const geometry::Pose2& motion) {
  // Last seen test (§II.A: "only use planes seen in the last few iterations").
  const int64_t gap = obs.iteration - latest.iteration;
  if (gap <= 0 || gap > options.last_seen_window) return -1.0;
  // The latest sighting's line and edges in the frame of `obs`.
  const Eigen::Vector2d normal = motion.Rotation() * latest.normal;
  const double d = latest.d - normal.dot(motion.Translation());
  const Eigen::Vector2d edge[2] = {motion * latest.edge[0], motion * latest.edge[1]};
  // Plane equation test.
  const double angle = std::acos(std::clamp(normal.dot(obs.normal), -1.0, 1.0));
  const double dd = std::abs(d - obs.d);
  if (angle > options.max_angle || dd > options.max_distance) return -1.0;
  // Bounding box test, along the wall and in height: adjacent planes must not match.
  const Eigen::Vector2d t = obs.Direction();
  double l0 = t.dot(edge[0]), l1 = t.dot(edge[1]);
  if (l0 > l1) std::swap(l0, l1);
  const double o_along = Overlap(l0, l1, t.dot(obs.edge[0]), t.dot(obs.edge[1]));
  const double o_height = Overlap(latest.z_min, latest.z_max, obs.z_min, obs.z_max);
  if (o_along < options.min_overlap || o_height < options.min_overlap) return -1.0;
  return (1.0 - angle / options.max_angle) + (1.0 - dd / options.max_distance) +
         std::min(o_along, 1.0) + std::min(o_height, 1.0) - 0.1 * static_cast<double>(gap - 1);
}

std::vector<int64_t> RegisterObservations(const std::vector<Observation>& observations,
                                          const PlaneStore& store, const WorldMap& world,
                                          const Trajectory& trajectory,
                                          const RegistrationOptions& options,
                                          const geometry::Pose2* now, std::vector<int64_t>* also) {
  std::vector<Candidate> candidates;
  for (int64_t id : store.recent) {
    const auto it = store.planes.find(id);
    if (it == store.planes.end()) continue;
    const Observation& latest = it->second.Latest();
    std::optional<geometry::Pose2> motion;  // from the frame `latest` was seen in to now
    if (now != nullptr) {
      const auto then = trajectory.poses.find(latest.iteration);
      if (then != trajectory.poses.end()) motion = now->Inverse() * then->second;
    }
    for (size_t k = 0; k < observations.size(); ++k) {
      const double score = MatchScore(latest, observations[k], options);
      if (score < 0.0) continue;
      if (motion && MatchScore(latest, observations[k], options, *motion) < 0.0) continue;
      candidates.emplace_back(score, k, id);
    }
  }
  // The best score wins; ties broken by observation index then id, for determinism.
  std::sort(candidates.begin(), candidates.end(), [](const auto& x, const auto& y) {
    if (std::get<0>(x) != std::get<0>(y)) return std::get<0>(x) > std::get<0>(y);
    if (std::get<1>(x) != std::get<1>(y)) return std::get<1>(x) < std::get<1>(y);
    return std::get<2>(x) < std::get<2>(y);
  });
  std::vector<int64_t> match(observations.size(), -1);
  std::map<int64_t, size_t> taken_by;  // rltplane -> the observation it took
  std::vector<bool> settled(observations.size(), false);
  // The rltplane an observation matched best that another piece of its surface took.
  std::vector<int64_t> piece_of(observations.size(), -1);
  for (const auto& [score, k, id] : candidates) {
    if (settled[k]) continue;
    const auto taken = taken_by.find(id);
    if (taken == taken_by.end()) {
      match[k] = id;
      taken_by.emplace(id, k);
      settled[k] = true;
    } else if (OnLineOf(observations[k], observations[taken->second], options)) {
      // A rltplane it matches took another piece of the same surface (the segmenter split
      // the wall): any lesser match is another surface that passed the tests, such as the
      // back of a door recess within the offset bound behind it. Registered there, it pulls the
      // pose across the hallway by the recess's depth. It is left to backtracking (§II.A end)
      // or a new rltplane, but for the one case below.
      piece_of[k] = id;
      settled[k] = true;
    }
  }
  // Such a piece takes another rltplane of the taken one's surface that no plane took, if that
  // one is the older (more sightings). The segmenter reports a wall in two pieces beside a door
  // or as one across it from one frame to the next, and the pieces and the whole go to two
  // rltplanes. Left out, the piece becomes a third and the wall's older rltplane is lost: only
  // the jambs of the door behind then place the pose along the room. Not the younger: a
  // duplicate is left to time out ungrouped (§II.B); fed, it can be grouped and placed turned by
  // a door's jambs, and the heading with it. Only after every other plane has its match, so that
  // no plane loses its own rltplane to a piece.
  for (const auto& [score, k, id] : candidates) {
    if (piece_of[k] < 0 || match[k] >= 0 || id == piece_of[k] || taken_by.count(id)) continue;
    if (store.planes.at(id).Count() <= store.planes.at(piece_of[k]).Count()) continue;
    if (!SameSurface(store, trajectory, id, piece_of[k], options)) continue;
    match[k] = id;
    taken_by.emplace(id, k);
  }
  if (also != nullptr)
    *also =
        AlsoSeenAs(observations, match, candidates, taken_by, store, world, trajectory, options);
  return match;
}

void MarkJumpedEnds(const std::vector<int64_t>& match, const PlaneStore& store,
                    const Trajectory& trajectory, const geometry::Pose2& pose,
                    std::vector<Observation>* observations, const RegistrationOptions& options) {
  for (size_t k = 0; k < observations->size(); ++k) {
    const auto it = match[k] >= 0 ? store.planes.find(match[k]) : store.planes.end();
    if (it == store.planes.end()) continue;
    Observation& obs = (*observations)[k];
    const auto& all = it->second.Observations();
    const Eigen::Vector2d t = pose.Rotation() * obs.Direction();
    for (int e = 0; e < 2; ++e) {
      if (obs.ViewCut(e)) continue;
      // The latest uncut sighting of this end with a known pose.
      for (size_t i = all.size(); i > 0; --i) {
        const Observation& then = all[i - 1];
        if (then.iteration < obs.iteration - options.end_memory) break;
        const auto seen_from = trajectory.poses.find(then.iteration);
        if (then.ViewCut(e) || seen_from == trajectory.poses.end()) continue;
        const Eigen::Vector2d jump = seen_from->second * then.edge[e] - pose * obs.edge[e];
        if (std::abs(t.dot(jump)) > options.end_jump) obs.cut[e] = true, obs.coarse[e] = false;
        break;
      }
    }
  }
}

}  // namespace relplane::mapper
