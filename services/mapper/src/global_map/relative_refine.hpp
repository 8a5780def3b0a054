#pragma once
// §II.D the averaging of a relative map: once the chain has placed a group's members, their
// orientations, points and lines are solved again from all the group's comparisons, not only the
// links of the chain.

#include "global_map/relative_map.hpp"

namespace relplane::mapper {

// Each member's orientation from all its comparisons with the others, the basis held; the points
// stay where the chain put them.
void RefineOrientations(const RelativeMapInputs& in, RelativeMap* map);

// Each placed point from all the static pairings between members, the orientations held.
void RefinePoints(const RelativeMapInputs& in, const ComparisonOptions& comparison,
                  RelativeMap* map);

// Each placed point moved across its wall to agree with its parallel members' lines, the points
// along the walls held.
void RefineLines(const RelativeMapInputs& in, const ComparisonOptions& comparison,
                 RelativeMap* map);

}  // namespace relplane::mapper
