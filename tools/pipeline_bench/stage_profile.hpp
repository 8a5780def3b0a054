#pragma once
// Each stage's own compute on the benchmark's clouds: the segmenter's and the mapper's libraries
// run in this process, one frame after another on one thread, fed through their services'
// message conversions and timed by the thread's CPU clock. Next to the pipeline's latencies this
// separates what the algorithms cost, and how that varies from frame to frame, from what
// transport and scheduling add.
//
// Two functions in two libraries: the segmenter's and the mapper's service shells have headers
// of the same names, so no source may see both.

#include <cstdint>
#include <string>
#include <vector>

namespace relplane::bench {

// Segments each encoded point_cloud_t with the options of `scenario`'s segmenter section;
// returns each frame's thread CPU time in ms and sets `plane_sets` to the encoded plane_set_t
// the service would publish. Throws std::runtime_error on a cloud that does not decode.
std::vector<double> ProfileSegmenter(const std::string& scenario,
                                     const std::vector<std::vector<uint8_t>>& clouds,
                                     std::vector<std::vector<uint8_t>>* plane_sets);

// Feeds each encoded plane_set_t to a mapper with `scenario`'s mapper options and does what the
// service does with the result (POSE with its covariance, MAP when changed and due, each
// encoded); returns each frame's thread CPU time in ms. Throws std::runtime_error on a plane set that does not decode.
std::vector<double> ProfileMapper(const std::string& scenario,
                                  const std::vector<std::vector<uint8_t>>& plane_sets);

}  // namespace relplane::bench
