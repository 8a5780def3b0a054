#pragma once
// Generated indoor worlds (generator `random_indoor`), so nobody can tune to a fixed set: rooms
// of varied sizes joined by corridors, with pillars, doorways, door recesses, and a route
// through them (straight legs, turns on the spot; a loop driven once or twice, or out to the
// last room and back). Everything follows from the seed.
//
// Valid by construction: the free space is carved into a grid, the walls are the grid's
// boundaries between free and solid cells, and the route runs along the centre lines of what
// was carved; pillars and doorways that would come within kRouteClearance of the route are not
// placed. The route's first waypoint is the origin.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace relplane::sim {

struct RandomIndoorParams {
  uint64_t seed = 1;
};

inline constexpr double kRouteClearance = 0.6;  // m from the route to any wall

struct IndoorLayout {
  // Floor-plan wall segments, free space on the left of from -> to.
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> walls;
  std::vector<Eigen::Vector2d> route;  // waypoints, the first at the origin
  bool closed = false;                 // a loop: the route returns to its first waypoint
  int laps = 1;
  bool drive_back = false;  // out and back
  std::string description;  // one line: rooms, corridors, pillars, route
};

IndoorLayout MakeRandomIndoor(const RandomIndoorParams& params);

}  // namespace relplane::sim
