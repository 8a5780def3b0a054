#pragma once
// The straight legs of a run (the true heading constant while the sensor moves) and the error
// along each leg its pose gained from the leg's first frame to its last: whether the mapper
// measures the distance driven short or long. A loop whose every leg is short by the same
// fraction still closes, so the pose graph has nothing to spread (§II.D chains groups along a
// leg); this says so where the loop closure cannot.

#include <cstdint>
#include <vector>

#include "relplane/accuracy/scenario_run.hpp"

namespace relplane::accuracy {

struct Leg {
  int64_t first_seq = 0;
  int64_t last_seq = 0;
  double length_m = 0.0;       // true distance driven, first frame to last
  double along_error_m = 0.0;  // along-leg error at the last frame minus that at the first
};

// Legs of at least `min_length_m`, over frames that have a pose; a frame without one (refused)
// does not end a leg, a change of true heading does.
std::vector<Leg> StraightLegs(const std::vector<FramePose>& poses, double min_length_m = 1.0);

// Sum of the legs' along errors over the sum of their lengths, in percent (0 without legs).
double AlongTrackPercent(const std::vector<Leg>& legs);

}  // namespace relplane::accuracy
