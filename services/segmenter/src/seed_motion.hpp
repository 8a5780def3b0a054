#pragma once
// Seeds from the previous frame that the sensor's motion carried out of EM's reach, put back
// where the motion of the seeds EM kept says they are. Private to the library.

#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/em.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter {

// Puts the seeds EM lost back where the sensor's motion carries them, runs EM again and keeps
// those that find their surface there (most of their previous support, where predicted); the
// others get no support, so pruning removes them. `seeds` are the previous frame's planes, the
// first of `*planes` their fits in this frame. Returns how many were kept.
int CarryLostSeeds(const Cloud& sample, const Options& options, const std::vector<EmPlane>& seeds,
                   float min_support, std::vector<EmPlane>* planes, Responsibilities* resp);

}  // namespace relplane::segmenter
