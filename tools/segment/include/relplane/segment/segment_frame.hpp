#pragma once
// One depth frame through the EM segmenter (the same library relplane-segmenter runs).

#include <cstdint>
#include <vector>

#include "relplane/segment/depth_frame.hpp"
#include "relplane/segment/plane_report.hpp"
#include "relplane/segmenter/segmenter.hpp"

namespace relplane::segment {

// Segments `frame` with `segmenter` (seeded by the frame before, as in a stream). With
// `labels`, also each point's plane index (-1: none); the segmenter must keep labels.
FramePlanes SegmentFrame(segmenter::Segmenter& segmenter, const DepthFrame& frame,
                         std::vector<int32_t>* labels = nullptr);

}  // namespace relplane::segment
