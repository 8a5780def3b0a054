#include "relplane/segment/segment_frame.hpp"

namespace relplane::segment {

FramePlanes SegmentFrame(segmenter::Segmenter& segmenter, const DepthFrame& frame,
                         std::vector<int32_t>* labels) {
  segmenter::Cloud cloud;
  cloud.x = frame.x;
  cloud.y = frame.y;
  cloud.z = frame.z;
  segmenter::Result result = segmenter.Segment(cloud);
  FramePlanes planes;
  planes.name = frame.name;
  planes.points = result.input_points;
  planes.invalid_points = result.dropped_nonfinite;
  planes.planes = std::move(result.planes);
  if (labels != nullptr) *labels = std::move(result.labels);
  return planes;
}

}  // namespace relplane::segment
