#pragma once
// §II.D end, on the published map: one wall seen as more than one rltplane (the loop was not
// closed on it, or it was only ever seen in pieces at the edge of the view) is shown once.

#include <vector>

#include "relplane/mapper/options.hpp"
#include "relplane/mapper/types.hpp"

namespace relplane::mapper {

// Drops a mapped wall lying inside another on the same line (of two each inside the other, the
// better-observed one stays), stretches the better-observed of two walls on the same line,
// facing the same way, over the other where they share most of the shorter one, and joins a
// piece known only by its line (no end known) to the wall on the same line that it may
// continue: that wall's facing end is not known and no other wall crosses the gap.
void MergeDuplicateWalls(std::vector<MappedPlane>* planes, const PublishedMapOptions& options = {},
                         const FitOptions& fit = {});

// The published map's walls as Mapper::Map draws them: MergeDuplicateWalls, each end drawn at the
// corner it meets (SnapEndsToCorners, `corner_radius`), then MergeDuplicateWalls again, since a
// wall drawn on to its corner may now hold a short piece it stopped short of before.
void CleanUpWalls(std::vector<MappedPlane>* planes, const PublishedMapOptions& options,
                  const FitOptions& fit);

}  // namespace relplane::mapper
