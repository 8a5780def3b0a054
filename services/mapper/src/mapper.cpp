#include "relplane/mapper/mapper.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "relplane/mapper/backtracking.hpp"
#include "relplane/mapper/global_map.hpp"
#include "relplane/mapper/grouping.hpp"
#include "relplane/mapper/map_cleanup.hpp"
#include "relplane/mapper/registration.hpp"
#include "relplane/mapper/regrouping.hpp"
#include "relplane/mapper/relative_map.hpp"

namespace relplane::mapper {
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
  last_iteration_ = iteration;
  std::vector<Observation> observations;
  for (const PlaneInput& input : planes) {
    auto obs = MakeObservation(input, iteration, options_.registration.max_wall_normal_z);
    if (!obs) continue;
    frustum_.Observe(obs->edge[0]);
    frustum_.Observe(obs->edge[1]);
    observations.push_back(std::move(*obs));
  }
  // Edges cut by the view are never static edges (§II.C).
  MarkOccludedEdges(&observations);
  for (Observation& obs : observations) {
    for (int e = 0; e < 2; ++e) obs.cut[e] = obs.cut[e] || frustum_.Clipped(obs.edge[e]);
  }
  const std::vector<int64_t> visible = Register(iteration, observations);  // §II.A
  UpdateGroups(state_, visible, iteration, options_.grouping);             // §II.B
  Regroup(state_, iteration, options_);                                    // §II.F
  Compare(iteration, visible);                                             // §II.C
  BuildMaps();                                                             // §II.D
  const PoseEstimate estimate = Localise(iteration, visible);              // §II.D, §II.E
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
  while (!state_.poses.empty() && state_.poses.begin()->first < iteration - 2000) {
    state_.poses.erase(state_.poses.begin());
  }
  while (!state_.fixed_poses.empty() && *state_.fixed_poses.begin() < iteration - 2000) {
    state_.fixed_poses.erase(state_.fixed_poses.begin());
  }
  return estimate;
}

std::vector<int64_t> Mapper::Register(int64_t iteration, std::vector<Observation>& observations) {
  std::vector<int64_t> match = RegisterObservations(observations, state_, options_.registration);
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
    geometry::Pose2 pose = pose_;
    if (!sightings.empty()) pose = mapper::Localise(sightings, pose_, frustum_, options_.localisation).pose;
    std::set<int64_t> taken(match.begin(), match.end());
    for (size_t k = 0; k < observations.size(); ++k) {
      if (match[k] >= 0) continue;
      match[k] = MatchGlobal(observations[k], pose, state_, taken, options_.backtrack);
      if (match[k] >= 0) taken.insert(match[k]);
    }
  }
  MarkJumpedEnds(match, state_, pose_, &observations);  // §II.C: another end, not the wall's
  std::vector<int64_t> visible;
  for (size_t k = 0; k < observations.size(); ++k) {
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
  std::set<PairKey> done;
  for (int64_t id : visible) {
    RltPlane* plane = state_.Plane(id);
    if (plane == nullptr) continue;
    for (int64_t g : plane->groups) {
      Group& group = state_.groups[g];
      for (int64_t other : group.members) {
        if (other == id || !std::binary_search(visible.begin(), visible.end(), other)) continue;
        // A frozen group keeps its relative map (§II.F); the comparison still learns (static
        // edges now, for localisation).
        if (!group.Frozen()) group.dirty = true;
        const PairKey key = KeyOf(id, other);
        if (!done.insert(key).second) continue;
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
  PoseEstimate estimate = mapper::Localise(sightings, pose_, frustum_, options_.localisation);
  if (initializing) estimate.status = PoseStatus::kInitializing;
  if (state_.first_iteration == iteration) estimate.pose = pose_;
  return estimate;
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
  MergeDuplicateWalls(&snapshot.planes);  // §II.D end
  for (const Group& g : state_.groups) {
    snapshot.groups.push_back({g.id, g.relative.basis, g.members});
  }
  return snapshot;
}

}  // namespace relplane::mapper
