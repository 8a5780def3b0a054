#pragma once
// New mixture components from the points no plane explains (K is unknown, so EM is seeded
// from the data between rounds).

#include <random>
#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/em.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter {

// Proposes up to options.proposals.max_per_round planes on the points `candidates` (indices
// into `points`). Each proposal comes from the best of options.proposals.trials local
// neighbourhoods: a flat neighbourhood (RMS below proposals.max_rms) gives a plane, scored by
// how many candidates lie within 2.5 sigma of it; the winner is refitted to those inliers and
// kept when at least `min_support` candidates support it. A neighbourhood is the seed's
// options.proposals.neighbours nearest candidates; "flat" also means its scatter is thin
// compared with its spread, which rejects patches across an edge. Deterministic for a given `rng`.
std::vector<EmPlane> ProposePlanes(const Cloud& points, std::vector<int> candidates,
                                   const Options& options, int min_support, std::mt19937* rng);

}  // namespace relplane::segmenter
