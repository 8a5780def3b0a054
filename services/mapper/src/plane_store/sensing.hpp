#pragma once
// §II.A an iteration's planes as the mapper takes them in: walls only (2½D), one per surface and
// iteration, each edge marked cut where the view, a nearer plane or the range hides the wall's
// end (§II.C: a cut edge is never a static edge). The sensor's view is learnt from them.

#include <cstdint>
#include <vector>

#include "localisation/frustum.hpp"
#include "plane_store/observation.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/types.hpp"

namespace relplane::mapper {

// The widest spacing of the sensor's samples along a wall at an edge that still places the wall's
// end by one sighting: √12 static_std, the width of a uniform error with the standard deviation
// the comparisons tell a static end by (§II.C).
double MaxEndSpacing(double static_std);

std::vector<Observation> Observe(int64_t iteration, const std::vector<PlaneInput>& planes,
                                 const RegistrationOptions& options, double static_std,
                                 LearnedFrustum* frustum);

}  // namespace relplane::mapper
