#pragma once
// World generators: hallways and offices as floor-plan wall segments. All walls go from
// z = 0 to the world's height unless said otherwise; the origin is where trajectories start.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace relplane::sim {

struct Rect;

// A hallway along +x centred on y = 0, from x = start to x = start + length.
struct StraightHallwayParams {
  double length = 14.0;
  double width = 2.0;
  double start = -1.0;      // x of the rear end
  bool closed_ends = true;  // end walls at both ends
};

// A rectangular loop of hallway (the paper's Fig. 5). The hallway's centre line is the
// rectangle (0,0) - (size.x - width, 0) - (size.x - width, size.y - width) - (0, size.y - width),
// so a robot starting at the origin heading +x drives along the bottom hallway.
// With recess_spacing > 0 the outer walls have door recesses: at every multiple of
// recess_spacing along each outer wall (measured from its corner, counter-clockwise) the wall
// is broken for recess_width and continues recess_depth further out, joined by two jambs. No
// recess comes within kRecessCornerClearance of a corner. They give the position along a
// hallway something to be fixed by: two parallel side walls alone do not.
struct HallwayLoopParams {
  Eigen::Vector2d size{16.0, 10.0};  // outer extent, metres
  double width = 2.0;                // hallway width
  double recess_spacing = 0.0;       // metres between recesses; 0: plain walls
  double recess_width = 1.0;         // along the wall
  double recess_depth = 0.3;         // behind the outer wall line
};
inline constexpr double kRecessCornerClearance = 1.5;

// A grid of rooms joined by doors in every wall between two rooms. Room (0, 0) is centred on
// the origin; room (i, j) is centred on (i * room_size.x, j * room_size.y).
struct OfficeParams {
  Eigen::Vector2i rooms{3, 2};
  Eigen::Vector2d room_size{5.0, 4.0};
  double door_width = 1.2;
  double door_height = 2.0;  // a lintel closes the wall above the door
  double frame_depth = 0.1;  // door jambs across the wall, 0 for none
};

// The generators append their rectangles to `out`; `height` is the wall height.
void AddStraightHallway(const StraightHallwayParams& p, double height, std::vector<Rect>* out);
void AddHallwayLoop(const HallwayLoopParams& p, double height, std::vector<Rect>* out);
void AddOffice(const OfficeParams& p, double height, std::vector<Rect>* out);

// A random clutter of `num_walls` vertical walls (random length, orientation, base and
// height) in a square of side `extent` centred on the origin, plus `num_tilted` rectangles in
// general position. For tests and benchmarks.
void AddRandomClutter(int num_walls, int num_tilted, double extent, uint64_t seed,
                      std::vector<Rect>* out);

}  // namespace relplane::sim
