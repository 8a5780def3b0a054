#pragma once
// What kind of world a run drives through, from the true poses alone: at each frame, do the
// walls in view fix (x, y, yaw)? A generated world is "observable" when every frame is, else it
// has unobservable stretches (a corridor with nothing along it in range, one wall in view while
// driving), told apart by the longest: under a second (entering a corridor, a turn past an
// opening) or longer. The mapper's targets differ between the kinds (issue 51).

#include <cstdint>
#include <string>
#include <vector>

#include "relplane/sim/simulation.hpp"

namespace relplane::accuracy {

struct WorldKind {
  int64_t frames = 0;
  int64_t unobservable_frames = 0;
  int64_t longest_stretch = 0;       // unobservable frames in a row
  double longest_stretch_s = 0.0;     // the same in simulated seconds
  std::vector<int64_t> unobservable;  // which frames

  bool Observable() const { return unobservable_frames == 0; }
  std::string Label() const {
    if (Observable()) return "observable";
    return longest_stretch_s < 1.0 ? "unobservable < 1 s" : "unobservable >= 1 s";
  }
};

// Casts a horizontal fan of rays (one per degree of the field of view, up to the range) at the
// sensor's height from every true pose. Each wall hit gives its line (one equation across it,
// levered by where its hits lie) and its orientation (weighed by its visible length and hits);
// each wall end with a hit close to it fixes the position along the wall. All to 1 cm (the
// lines and ends) as the observability test of the mapper (observability.hpp) takes them.
WorldKind ClassifyWorld(const sim::Simulation& simulation);

}  // namespace relplane::accuracy
