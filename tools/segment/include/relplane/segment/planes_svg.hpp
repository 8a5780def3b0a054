#pragma once
// A picture of the planes found in organized frames, one panel per frame in the image plane:
// pixels coloured by plane (grey: no plane, black: no depth) and each plane's extent polygon
// projected with a pinhole of the given focal length centred on the image.

#include <cstdint>
#include <string>
#include <vector>

#include "relplane/segment/depth_frame.hpp"
#include "relplane/segmenter/cloud.hpp"

namespace relplane::segment {

struct LabelledFrame {
  DepthFrame frame;                              // organized
  std::vector<int32_t> labels;                   // per point: index in `planes`, or -1
  std::vector<segmenter::DetectedPlane> planes;  // sensor frame
};

// The SVG document.
std::string PlanesSvg(const std::vector<LabelledFrame>& frames, double focal_px);

}  // namespace relplane::segment
