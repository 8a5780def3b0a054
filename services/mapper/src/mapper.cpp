#include "relplane/mapper/mapper.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>
#include <vector>

#include "relplane/mapper/backtracking.hpp"
#include "relplane/mapper/global_map.hpp"
#include "relplane/mapper/grouping.hpp"
#include "relplane/mapper/map_cleanup.hpp"
#include "relplane/mapper/registration.hpp"
#include "relplane/mapper/regrouping.hpp"
#include "relplane/mapper/relative_map.hpp"

namespace relplane::mapper {

namespace {

// Turning on the spot (the paths' corners): the heading is seen whatever the walls leave open,
// and a sensor turning faster than MotionOptions::turn_rate is taken not to move on; faster by
// more than twice the heading's own error (PoseEstimate::yaw_sigma), so that a heading from a
// door jamb alone, wobbling frame to frame, does not pass for a turn.
bool Turning(const geometry::Pose2& from, const geometry::Pose2& to, int64_t iterations,
             double turn_rate, double yaw_sigma = 0.0) {
  return std::abs(std::remainder(to.yaw - from.yaw, 2.0 * M_PI)) >
         turn_rate * static_cast<double>(iterations) + 2.0 * yaw_sigma;
}

}  // namespace

int MarkViewCuts(const LearnedFrustum& frustum, MapperState& state) {
  int marked = 0;
  for (auto& entry : state.planes) {
    const int64_t id = entry.first;
    RltPlane& plane = entry.second;  // named, not a structured binding: the lambda below uses it
    const auto& all = plane.Observations();
    std::set<int64_t> changed;  // iterations with a newly cut edge
    for (size_t i = 0; i < all.size(); ++i) {
      for (int e = 0; e < 2; ++e) {
        if (all[i].cut[e] || !frustum.Clipped(all[i].edge[e], all[i].edge[1 - e])) continue;
        plane.MarkCut(i, e);
        changed.insert(all[i].iteration);
        ++marked;
      }
    }
    if (changed.empty()) continue;
    // A sighting kept from one of those observations carries its cut flags.
    auto revise = [&](SeenWall& seen) {
      const Observation* obs = seen.valid ? plane.At(seen.iteration) : nullptr;
      if (obs == nullptr || changed.count(seen.iteration) == 0) return;
      for (int e = 0; e < 2; ++e) seen.cut[e] = seen.cut[e] || obs->cut[e];
    };
    revise(plane.first_seen);
    for (Group& group : state.groups) {
      if (std::find(group.members.begin(), group.members.end(), id) == group.members.end()) {
        continue;
      }
      if (auto it = group.seen.find(id); it != group.seen.end()) revise(it->second);
      if (auto it = group.seen_fixed.find(id); it != group.seen_fixed.end()) revise(it->second);
      for (auto it = group.shows_end.begin(); it != group.shows_end.end();) {
        it = std::get<0>(it->first) == id ? group.shows_end.erase(it) : std::next(it);
      }
      group.dirty = true;
    }
  }
  return marked;
}

Mapper::Mapper(MapperOptions options) : options_(std::move(options)) {
  pose_ = {options_.start_pose.x, options_.start_pose.y, options_.start_pose.yaw};
}

PoseEstimate Mapper::Process(int64_t iteration, const std::vector<PlaneInput>& planes) {
  if (iteration <= last_iteration_) return {pose_, PoseStatus::kLost, 0};
  if (state_.first_iteration < 0) {
    state_.first_iteration = iteration;
    state_.poses[iteration] = pose_;
    state_.fixed_poses.insert(iteration);
  }
  predicted_ = Predict(iteration, &motion_known_);
  previous_iteration_ = last_iteration_;
  last_iteration_ = iteration;
  std::vector<Observation> observations;
  for (const PlaneInput& input : planes) {
    auto obs = MakeObservation(input, iteration, options_.registration.max_wall_normal_z);
    if (!obs) continue;
    frustum_.Observe(obs->edge[0]);
    frustum_.Observe(obs->edge[1]);
    frustum_.ObserveSampling(*obs);
    observations.push_back(std::move(*obs));
  }
  // §II.A: one plane per surface and iteration, as an rltplane stores them.
  DropRepeatedSightings(&observations, options_.registration,
                        [this](const Eigen::Vector2d& edge) { return frustum_.Clipped(edge); });
  // Edges cut by the view are never static edges (§II.C), nor were they before the view's
  // range was learnt: a wall's far end at the range creeps along with the sensor, so the
  // sightings before agree with it and it passed for the wall's end (an unseen office: a wall
  // seen through a door was mapped 1.3 m short of its corner and again as a second plane).
  if (frustum_.RangeLimit() < judged_range_limit_) {
    judged_range_limit_ = frustum_.RangeLimit();
    MarkViewCuts(frustum_, state_);
  }
  MarkOccludedEdges(&observations, options_.registration);
  for (Observation& obs : observations) {
    for (int e = 0; e < 2; ++e) {
      obs.cut[e] = obs.cut[e] || frustum_.Clipped(obs.edge[e], obs.edge[1 - e]);
    }
  }
  state_.angular_step = frustum_.AngularStep();  // for the groups' priors (group_prior.cpp)
  const std::vector<int64_t> visible = Register(iteration, observations);  // §II.A
  UpdateGroups(state_, visible, iteration, options_.grouping);             // §II.B
  Regroup(state_, iteration, options_);                                    // §II.F
  Compare(iteration, visible);                                             // §II.C
  BuildMaps();                                                             // §II.D
  const PoseEstimate estimate = Localise(iteration, visible);              // §II.D, §II.E
  MakePoseTie(estimate);
  pose_ = estimate.pose;
  state_.poses[iteration] = pose_;
  if (estimate.status == PoseStatus::kTracking) state_.fixed_poses.insert(iteration);
  for (int64_t id : visible) {
    RltPlane* plane = state_.Plane(id);
    if (plane == nullptr) continue;
    plane->latest_pose = pose_;
    plane->latest_pose_known = true;
    if (!plane->first_seen.valid) plane->first_seen = SeenFrom(plane->Latest(), pose_);
  }
  DropOldObservations(state_, visible, iteration, options_);  // bounded memory (§II.F)
  const int64_t forget_before = iteration - options_.motion.pose_history;
  while (!state_.poses.empty() && state_.poses.begin()->first < forget_before) {
    state_.poses.erase(state_.poses.begin());
  }
  while (!state_.fixed_poses.empty() && *state_.fixed_poses.begin() < forget_before) {
    state_.fixed_poses.erase(state_.fixed_poses.begin());
  }
  return estimate;
}

void Mapper::NoteClosing(const std::vector<Sighting>& chain, const geometry::Pose2& pose,
                         int64_t oldest) {
  if (oldest < 0 || chain.empty()) return;
  // The pose is the chain's only where every wall it came from was placed by a group well after
  // the re-seen one: once the old walls are in view again they set it too.
  int64_t newest = -1;
  Eigen::Matrix2d information = Eigen::Matrix2d::Zero();
  for (const Sighting& s : chain) {
    auto by = state_.placed_by.find(s.plane->Id());
    if (by == state_.placed_by.end() || by->second - oldest <= options_.grouping.recent_groups) {
      return;
    }
    newest = std::max(newest, by->second);
    if (s.world.known == Known::kAngle) continue;
    const Eigen::Vector2d n = NormalOf(s.world.alpha);
    information += n * n.transpose();
  }
  // Where the chain's walls leave a direction open the pose is the motion model's along it
  // (§II.E): as good as the sensor's position while it turns on the spot (held still), but only
  // a learnt velocity's guess while it moves. The tie then holds the two groups across that
  // direction only, or not at all.
  auto before = state_.poses.lower_bound(previous_iteration_ - 1);
  const bool turning = before != state_.poses.end() && before->first < previous_iteration_ &&
                       Turning(before->second, pose_, previous_iteration_ - before->first,
                               options_.motion.turn_rate);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(information);
  closing_open_ = false;
  if (!turning && eig.eigenvalues()(1) < kOpenInformation) return;  // both directions open
  if (!turning && eig.eigenvalues()(0) < kOpenInformation) {
    closing_open_ = true;
    const Eigen::Vector2d u = eig.eigenvectors().col(0);
    closing_open_alpha_ = std::atan2(u.y(), u.x());
  }
  closing_ = true;
  closing_pose_ = pose;
  closing_from_ = newest;
  closing_to_ = oldest;
}

void Mapper::MakePoseTie(const PoseEstimate& estimate) {
  if (!closing_) return;
  closing_ = false;
  if (estimate.status != PoseStatus::kTracking) return;
  const Group& from = state_.groups.at(static_cast<size_t>(closing_from_));
  const Group& to = state_.groups.at(static_cast<size_t>(closing_to_));
  // A loop that closes where the chain already has the sensor has nothing to spread: no tie, and
  // the graph is not solved for it.
  Eigen::Vector2d jump(estimate.pose.x - closing_pose_.x, estimate.pose.y - closing_pose_.y);
  if (closing_open_) {
    jump = NormalOf(closing_open_alpha_).dot(jump) * NormalOf(closing_open_alpha_);
  }
  if (jump.norm() < options_.graph.tie_min_jump &&
      std::abs(geometry::WrapAngle(estimate.pose.yaw - closing_pose_.yaw)) < options_.graph.tie_min_turn) {
    return;
  }
  PoseTie tie;
  tie.a_group = closing_from_;
  tie.b_group = closing_to_;
  tie.a_basis = from.relative.basis;
  tie.b_basis = to.relative.basis;
  tie.a_ref = from.relative.BasisRef();
  tie.b_ref = to.relative.BasisRef();
  tie.has_open = closing_open_;
  tie.open_alpha = geometry::WrapAngle(closing_open_alpha_ - from.placement.yaw);
  tie.a = from.placement.Inverse() * closing_pose_;
  tie.b = to.placement.Inverse() * estimate.pose;
  // A few per loop driven (only the first sighting of an old wall again closes it): bounded all
  // the same, for runs of hours.
  if (state_.pose_ties.size() >= static_cast<size_t>(options_.graph.max_pose_ties)) {
    state_.pose_ties.erase(state_.pose_ties.begin());
  }
  state_.pose_ties.push_back(tie);
  ++state_.pose_ties_made;
}

std::vector<int64_t> Mapper::Register(int64_t iteration, std::vector<Observation>& observations) {
  // §II.A compares each plane with a rltplane's latest sighting untransformed, which holds from
  // one iteration to the next but not over a few while turning; a match must also hold from
  // the pose now, as far as it is known: the last pose, turned on by the last iteration's turn
  // while turning on the spot (at the corners' 0.8 rad/s a wall 4 m away moves 0.1 m along
  // itself per iteration). See RegisterObservations.
  geometry::Pose2 now = pose_;
  const auto last = state_.poses.find(previous_iteration_ - 1);
  if (previous_iteration_ == iteration - 1 && last != state_.poses.end() &&
      Turning(last->second, pose_, 1, options_.motion.turn_rate)) {
    now.yaw = pose_.yaw + geometry::WrapAngle(pose_.yaw - last->second.yaw);
  }
  std::vector<int64_t> also;  // a line's older rltplane, as well (RegisterObservations)
  std::vector<int64_t> match =
      RegisterObservations(observations, state_, options_.registration, &now, &also);
  // §II.A end: unmatched planes are transformed with the current position (from the planes that
  // did match) and compared to the global map before becoming new rltplanes.
  if (std::find(match.begin(), match.end(), -1) != match.end() && !state_.global.empty()) {
    std::vector<Sighting> sightings;
    for (size_t k = 0; k < observations.size(); ++k) {
      auto it = match[k] >= 0 ? state_.global.find(match[k]) : state_.global.end();
      if (it != state_.global.end()) {
        sightings.push_back({&observations[k], state_.Plane(match[k]), it->second});
      }
    }
    geometry::Pose2 pose = predicted_;
    if (!sightings.empty()) {
      pose = mapper::Localise(sightings, predicted_, frustum_, options_.localisation, held_).pose;
    }
    std::set<int64_t> taken(match.begin(), match.end());
    taken.insert(also.begin(), also.end());
    int64_t oldest = -1;  // the oldest group placing a wall matched by backtracking
    for (size_t k = 0; k < observations.size(); ++k) {
      if (match[k] >= 0) continue;
      match[k] = MatchGlobal(observations[k], pose, state_, taken, options_.backtrack);
      if (match[k] < 0) continue;
      taken.insert(match[k]);
      if (auto by = state_.placed_by.find(match[k]); by != state_.placed_by.end()) {
        oldest = oldest < 0 ? by->second : std::min(oldest, by->second);
      }
    }
    NoteClosing(sightings, pose, oldest);
  }
  MarkJumpedEnds(match, state_, pose_, &observations, options_.registration);  // §II.C: another end, not the wall's
  std::vector<int64_t> visible;
  for (size_t k = 0; k < observations.size(); ++k) {
    if (match[k] >= 0 && also[k] >= 0) {
      state_.Plane(also[k])->Add(Observation(observations[k]));  // both ends cut: no end to mark
      visible.push_back(also[k]);
    }
    if (match[k] >= 0) {
      state_.Plane(match[k])->Add(std::move(observations[k]));
      visible.push_back(match[k]);
    } else {
      const int64_t id = state_.next_id++;
      state_.planes.emplace(id, RltPlane(id, std::move(observations[k]),
                                         options_.comparison.phase_hysteresis,
                                         options_.max_observations));
      state_.ungrouped.push_back(id);
      visible.push_back(id);
    }
  }
  // Recently seen rltplanes are the only registration candidates next time.
  state_.recent.insert(visible.begin(), visible.end());
  for (auto it = state_.recent.begin(); it != state_.recent.end();) {
    const RltPlane* plane = state_.Plane(*it);
    if (plane == nullptr ||
        iteration - plane->LastSeen() >= options_.registration.last_seen_window) {
      it = state_.recent.erase(it);
    } else {
      ++it;
    }
  }
  std::sort(visible.begin(), visible.end());
  return visible;
}

void Mapper::Compare(int64_t iteration, const std::vector<int64_t>& visible) {
  for (int64_t id : visible) {
    RltPlane* plane = state_.Plane(id);
    if (plane == nullptr) continue;
    plane->static_now[0] = plane->static_now[1] = false;
    plane->static_now_iteration = iteration;
  }
  // Pairs already updated, by their planes' indices in `visible` (sorted): a flag matrix, not a
  // set of keys, whose nodes cost more than the look-ups they saved.
  const size_t n = visible.size();
  std::vector<char> done(n * n, 0);
  for (size_t i = 0; i < n; ++i) {
    const int64_t id = visible[i];
    RltPlane* plane = state_.Plane(id);
    if (plane == nullptr) continue;
    const size_t ii =
        static_cast<size_t>(std::lower_bound(visible.begin(), visible.end(), id) - visible.begin());
    for (int64_t g : plane->groups) {
      Group& group = state_.groups[g];
      for (int64_t other : group.members) {
        if (other == id) continue;
        const auto found = std::lower_bound(visible.begin(), visible.end(), other);
        if (found == visible.end() || *found != other) continue;
        // A frozen group keeps its relative map (§II.F); the comparison still learns (static
        // edges now, for localisation).
        if (!group.Frozen()) group.dirty = true;
        const PairKey key = KeyOf(id, other);
        const size_t jj = static_cast<size_t>(found - visible.begin());
        char& pair_done = done[std::min(ii, jj) * n + std::max(ii, jj)];
        if (pair_done) continue;
        pair_done = 1;
        auto it = state_.comparisons.try_emplace(key, key.first, key.second).first;
        it->second.Update(*state_.Plane(key.first), *state_.Plane(key.second), iteration,
                          options_.comparison, options_.registration.last_seen_window);
      }
    }
  }
}

void Mapper::BuildMaps() {
  for (size_t g = 0; g < state_.groups.size(); ++g) {
    if (state_.groups[g].dirty) {
      BuildGlobalMap(state_, g, options_);
      return;
    }
  }
}

PoseEstimate Mapper::Localise(int64_t iteration, const std::vector<int64_t>& visible) {
  std::vector<Sighting> sightings;
  std::vector<Placement> provisional;
  provisional.reserve(visible.size());
  const bool initializing = state_.global.empty();
  const geometry::Pose2 start{options_.start_pose.x, options_.start_pose.y,
                              options_.start_pose.yaw};
  for (int64_t id : visible) {
    const RltPlane* plane = state_.Plane(id);
    if (plane == nullptr || plane->LastSeen() != iteration) continue;
    if (!initializing) {
      auto it = state_.global.find(id);
      if (it != state_.global.end()) sightings.push_back({&plane->Latest(), plane, it->second});
    } else if (plane->FirstSeen() == state_.first_iteration) {
      // Before the first group: the walls' lines as first seen from the start pose.
      provisional.push_back(PlacementOf(plane->Observations().front(), start, -1));
      sightings.push_back({&plane->Latest(), plane, provisional.back()});
    }
  }
  bool ends_seen = false;
  const int predicted_for = motion_known_ && !state_.fixed_poses.empty()
                                ? static_cast<int>(iteration - *state_.fixed_poses.rbegin())
                                : 0;
  auto localise = [&](const geometry::Pose2& previous) {
    PoseEstimate est = mapper::Localise(sightings, previous, frustum_, options_.localisation, held_,
                                        predicted_for);
    if (est.status != PoseStatus::kMotionModel || motion_known_ || ends_seen) return est;
    // The walls leave a direction open and the motion is not known (the start, moving off
    // after a turn on the spot; not while turning): the wall ends seen from poses the walls fixed
    // may show the motion along it (§II.E). Not where the motion is known: an end seen from
    // another place is off along its wall by centimetres (beside a door jamb, 1-9 cm in the
    // noise-free office, whose ATE went from 0.003 to 0.013 m), which the learnt velocity is not.
    // Looked up only then, as it goes through every kept observation of the walls in view.
    ends_seen = true;
    for (Sighting& x : sightings) {
      for (int e = 0; e < 2; ++e) {
        const SeenWall seen = EndSeenFromFixedPoses(state_, *x.plane, e);
        x.end_seen[e] = seen.valid;
        if (seen.valid) x.end[e] = seen.edge[e];
      }
    }
    return mapper::Localise(sightings, previous, frustum_, options_.localisation, held_);
  };
  PoseEstimate estimate = localise(predicted_);
  if (previous_iteration_ >= 0 &&
      Turning(pose_, estimate.pose, iteration - previous_iteration_, options_.motion.turn_rate,
              estimate.yaw_sigma)) {
    // The turn starts now: the sensor did not walk on after all.
    estimate = localise(pose_);
  }
  if (!initializing && estimate.planes > 0) last_walled_ = iteration;
  if (estimate.status == PoseStatus::kLost && sightings.empty() && !initializing &&
      last_walled_ >= 0 && iteration - last_walled_ <= options_.motion.max_coast) {
    // No mapped wall in view for a moment: the segmenter reported a wall's two pieces beside a
    // door as one over the lintel, which registered to neither of their rltplanes, and the
    // door's jambs were not mapped yet (office_other_sensor at 1 cm). Localise kept the pose it
    // started from, the motion model's (§II.E) as along a direction the walls leave open: the
    // learnt velocity, or held still where no motion is known. That is a pose, not LOST; not
    // where walls were in view and disagreed (Localise left them all out), nor for long.
    estimate.status = PoseStatus::kMotionModel;
  }
  const bool held = !motion_known_ && estimate.status == PoseStatus::kMotionModel &&
                    !estimate.end_moved;
  held_ = held ? held_ + 1 : 0;
  if (initializing) estimate.status = PoseStatus::kInitializing;
  if (state_.first_iteration == iteration) estimate.pose = pose_;
  return estimate;
}

geometry::Pose2 Mapper::Predict(int64_t iteration, bool* known) const {
  *known = false;
  // Constant velocity in the sensor's frame, learnt from the poses the walls fixed in every
  // direction: where they leave one open (a hallway between door frames) the position along it
  // moves on instead of standing still as the §II.E motion model alone would, which left it
  // lagging by metres until the next door frame (and then matched that frame to the wrong door).
  const MotionOptions& o = options_.motion;
  const int64_t kWindow = o.window, kMinSpan = o.min_span, kMaxGap = o.max_gap;
  const std::set<int64_t>& fixed = state_.fixed_poses;
  if (fixed.empty() || last_iteration_ < 0 || iteration - last_iteration_ > kMaxGap) return pose_;
  // The latest stretch of fixed poses long enough to learn from. A fixed pose or two after a
  // long spell of the §II.E motion model is no stretch, and must not make the velocity unknown:
  // the stretch before it still tells it, as long as the heading has not turned since (moving
  // off after a turn on the spot, the motion is not known). A door jamb fixed the pose for two
  // iterations after 68 of a room's one wall face ahead; the position then stood still once
  // that face stopped registering, and the next room was mapped 9 cm back (office_other_sensor,
  // σ = 1 cm, seed 23).
  int64_t i1 = *fixed.rbegin(), i0 = i1;
  auto p0 = state_.poses.end(), p1 = state_.poses.end();
  for (int stretch = 0;; ++stretch) {
    i0 = *fixed.lower_bound(i1 - kWindow);
    p0 = state_.poses.find(i0), p1 = state_.poses.find(i1);
    if (p0 == state_.poses.end() || p1 == state_.poses.end()) return pose_;
    if (stretch > 0 && Turning(p1->second, pose_, kMinSpan, o.turn_rate)) return pose_;
    // Fixed poses must be consecutive enough to be one stretch of motion.
    const auto in_stretch =
        static_cast<int64_t>(std::distance(fixed.lower_bound(i0), fixed.upper_bound(i1)));
    if (i1 - i0 >= kMinSpan && in_stretch >= (i1 - i0) / 2) break;
    const auto first = fixed.find(i0);
    if (first == fixed.begin() || stretch + 1 >= o.max_stretches) return pose_;
    i1 = *std::prev(first);
  }
  // The median of the steps between consecutive fixed poses, not the way from the first to the
  // last: a fixed pose that the walls set right (a wrong static edge let go, 8 cm back) is not
  // motion, and taken from end to end it slowed the learnt velocity by a fifth, which the open
  // stretch after it (a hallway's side walls only, 48 iterations) walked into 0.38 m.
  std::vector<double> steps;
  for (auto k = fixed.lower_bound(i0); k != fixed.end() && *k < i1; ++k) {
    const int64_t j = *std::next(k);
    auto a = state_.poses.find(*k), b = state_.poses.find(j);
    if (j - *k > 2 || a == state_.poses.end() || b == state_.poses.end()) continue;
    const Eigen::Vector2d d = b->second.Rotation().inverse() *
                              (b->second.Translation() - a->second.Translation()) /
                              static_cast<double>(j - *k);
    steps.push_back(d.x());
  }
  if (steps.empty()) return pose_;
  // A span of turning on the spot learns a velocity of nought, which says nothing of how the
  // sensor moves off once the turn ends (the paths' corners).
  *known = !Turning(p0->second, p1->second, i1 - i0, o.turn_rate);
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  // Only the part along the heading: the platform drives forwards (the paper's robot, the
  // simulator's paths), and a sideways part is the noise of the fixed poses, which would walk
  // the position off along an open direction.
  const Eigen::Vector2d step(std::clamp(steps[steps.size() / 2], -options_.localisation.max_step,
                                         options_.localisation.max_step), 0.0);
  // Turning on the spot, standing still is the motion: the heading turned over the last iteration
  // and over the last two. A heading from short walls alone wobbles back and forth by more than a
  // turn's step, but its wobbles do not add up: walking through a door with only its 0.15 m jambs
  // in view, headings 0.013-0.019 rad apart frame to frame passed for a turn each, the position
  // stood still on three of eight iterations, and the next room was mapped 5 cm back
  // (office_other_sensor, σ = 1 cm, seed 41: ATE 0.049 m).
  auto before = state_.poses.lower_bound(last_iteration_ - 1);
  if (before != state_.poses.end() && before->first < last_iteration_ &&
      Turning(before->second, pose_, last_iteration_ - before->first, o.turn_rate)) {
    auto earlier = state_.poses.lower_bound(before->first - 1);
    if (earlier == state_.poses.end() || earlier->first >= before->first ||
        Turning(earlier->second, pose_, last_iteration_ - earlier->first, o.turn_rate)) {
      *known = true;
      return pose_;
    }
  }
  const double frames = static_cast<double>(iteration - last_iteration_);
  const Eigen::Vector2d moved = pose_.Translation() + pose_.Rotation() * step * frames;
  return {moved.x(), moved.y(), pose_.yaw};
}

bool Mapper::TakeMapChanged() {
  const bool changed = state_.map_changed;
  state_.map_changed = false;
  return changed;
}

MapSnapshot Mapper::Map() const {
  MapSnapshot snapshot;
  for (const auto& [id, placed] : state_.global) {
    const RltPlane& plane = state_.planes.at(id);
    if (placed.known == Known::kAngle) continue;
    const Eigen::Vector2d n = NormalOf(placed.alpha);
    Eigen::Vector2d lo, hi;
    WallEnds(state_, plane, placed, &lo, &hi);
    const double z0 = plane.ZMin() + Height(), z1 = plane.ZMax() + Height();
    MappedPlane m;
    m.id = id;
    m.normal = Eigen::Vector3d(n.x(), n.y(), 0.0);
    m.d = -n.dot(placed.point);
    m.vertices = {{lo.x(), lo.y(), z0}, {hi.x(), hi.y(), z0}, {hi.x(), hi.y(), z1},
                  {lo.x(), lo.y(), z1}};
    const Eigen::Vector2d mid = 0.5 * (lo + hi);
    m.centroid = Eigen::Vector3d(mid.x(), mid.y(), 0.5 * (z0 + z1));
    m.observations = plane.Count();
    m.both_ends_known =
        placed.known == Known::kPoint && (placed.has_other || plane.FullLengthKnown());
    m.end_known[0] = placed.known == Known::kPoint && (placed.ref == 0 || m.both_ends_known);
    m.end_known[1] = placed.known == Known::kPoint && (placed.ref == 1 || m.both_ends_known);
    snapshot.planes.push_back(std::move(m));
  }
  CleanUpWalls(&snapshot.planes, options_.published_map);  // §II.D end
  for (const Group& g : state_.groups) {
    snapshot.groups.push_back({g.id, g.relative.basis, g.members});
  }
  return snapshot;
}

}  // namespace relplane::mapper
