#pragma once
// §II.A Registering planes: each untransformed plane of this iteration is matched against the
// latest untransformed observation of recently seen rltplanes.

#include <cstdint>
#include <functional>
#include <vector>

#include "global_map/world_map.hpp"
#include "motion/trajectory.hpp"
#include "plane_store/observation.hpp"
#include "plane_store/plane_store.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// The score of matching `obs` to a rltplane whose latest observation is `latest`, or a negative
// number when a test fails: last seen within the window, plane equations within bounds,
// sufficient bounding-box overlap. Higher is better (each test adds how well it passed).
// `motion` maps the sensor frame `latest` was seen in into the one `obs` is seen in (the
// identity: compared untransformed, as §II.A does).
double MatchScore(const Observation& latest, const Observation& obs,
                  const RegistrationOptions& options, const geometry::Pose2& motion = {});

// Drops, from one iteration's planes, each one that lies along another plane of the same
// iteration fitted to more points (normals within the plane-equation test, its middle on the
// other's line, overlapping it along the wall, or touching it and going on past its end only
// where `at_view_edge` says the view cuts it; overlapping it in height): the segmenter has
// reported a stretch of one surface twice (a piece at a room corner or beside a door jamb,
// fitted a few degrees off, beside the whole wall), or split off its part nearest the view's
// edge. Both match the same rltplane (§II.A), which stores one plane per iteration (Fig. 1), so
// the lesser one would become a new rltplane and be mapped as the wall's duplicate. The kept
// plane is extended over the dropped one's reach at the view's edge.
void DropRepeatedSightings(
    std::vector<Observation>* observations, const RegistrationOptions& options,
    const std::function<bool(const Eigen::Vector2d&)>& at_view_edge = nullptr);

// For each observation, the id of the rltplane it registers to, or -1 (a new rltplane). Only
// rltplanes in `store.recent` are compared, so the cost does not grow with the map. Each
// rltplane takes at most one observation; the highest scores are assigned first. A plane on
// the line of one that took a rltplane it matches is a piece of that surface and takes no
// lesser match, but another rltplane of that surface with more sightings that no plane took
// (its latest sighting, moved from the pose it was seen from into the taken one's, on that one's
// line).
// With `now` (the sensor's pose this iteration, as far as it is known), a match must also pass
// the tests with the latest observation moved from the pose it was seen from (`trajectory.poses`)
// into it. Compared untransformed, a sighting a few iterations old is judged from where the
// sensor was then: a turn on the spot of 0.12 rad moves a face 4 m away 0.5 m along the wall,
// onto a wall behind it, which then registers to the face's rltplane and is mapped off its
// place, and twice. The moved test only refuses: a plane it alone matches is left to
// backtracking (§II.A end) or a new rltplane, as untransformed. Letting it match as well
// registers the jambs of a door seen before a turn to planes of the next room.
// With `also`, for each observation: another rltplane it is added to as well, or -1. That is
// the wall's older, mapped rltplane when the observation is a line only (both ends cut by the
// view) and the rltplane it registered to is a younger one the map does not place (AlsoSeenAs
// in registration.cpp).
std::vector<int64_t> RegisterObservations(const std::vector<Observation>& observations,
                                          const PlaneStore& store, const WorldMap& world,
                                          const Trajectory& trajectory,
                                          const RegistrationOptions& options,
                                          const geometry::Pose2* now = nullptr,
                                          std::vector<int64_t>* also = nullptr);

// After matching: an end seen uncut now that lies far from where the same rltplane's end was
// last seen uncut (both placed on the map with the poses then and now, over the last few
// seconds) is another end, not the wall's: a wall seen whole (a door wall from across the
// room) is later seen in pieces, and the piece continuing it has a new end at the door; or a
// piece grows into the whole wall. Such an end is marked cut, so it never becomes the static
// edge (§II.C) the rltplane learnt at the other place: the end mapped metres away would be
// taken for it. `pose` is the latest estimate (one frame's motion is far below the jump).
void MarkJumpedEnds(const std::vector<int64_t>& match, const PlaneStore& store,
                    const Trajectory& trajectory, const geometry::Pose2& pose,
                    std::vector<Observation>* observations,
                    const RegistrationOptions& options = {});

}  // namespace relplane::mapper
