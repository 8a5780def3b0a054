#pragma once
// point_cloud_t -> Cloud and Result -> plane_set_t: the only place the segmenter meets LCM
// types.

#include <relplane/plane_set_t.hpp>
#include <relplane/point_cloud_t.hpp>
#include <string>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/segmenter.hpp"

namespace relplane::segmenter {

// Copies the message's points; false with a reason when its arrays disagree with num_points.
bool FromPointCloud(const point_cloud_t& msg, Cloud* cloud, std::string* reason);
// The same without a copy: swaps the message's arrays with the cloud's, so both keep their
// capacity for the next frame.
bool TakePointCloud(point_cloud_t* msg, Cloud* cloud, std::string* reason);

// The planes of one cloud, ids = index in the set, sensor frame, same utime/seq as the cloud.
plane_set_t ToPlaneSet(const Result& result, int64_t utime, int64_t seq);
// The same into `msg`, reusing its arrays' capacity.
void ToPlaneSet(const Result& result, int64_t utime, int64_t seq, plane_set_t* msg);

}  // namespace relplane::segmenter
