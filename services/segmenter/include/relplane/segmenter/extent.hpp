#pragma once
// After EM: split each plane's support into connected pieces and describe each piece.

#include <cstdint>
#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/em.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter {

// For every plane, the points labelled with it are binned into an occupancy grid in the
// plane's own coordinates (options.cell_size); occupied cells within options.cell_reach of one
// another form one piece, so two walls on one line with a door between them are two planes.
// Each piece with at least options.min_points points is refitted by least squares and gets its
// centroid, RMS, support count and extent polygon (a rectangle aligned with the vertical for a
// vertical plane, the convex hull otherwise); its normal points towards the sensor at the
// origin. Pieces come back in order of decreasing support.
// `ambiguous` (from AssignPoints, may be empty) marks points on the strip where two planes
// meet: they belong to a piece but cannot connect pieces. `piece_labels` (optional) receives
// each point's index into the result, -1 for points in no piece.
std::vector<DetectedPlane> DescribePieces(const Cloud& cloud, const std::vector<int32_t>& labels,
                                          const std::vector<uint8_t>& ambiguous,
                                          const std::vector<EmPlane>& planes,
                                          const Options& options,
                                          std::vector<int32_t>* piece_labels = nullptr);

}  // namespace relplane::segmenter
