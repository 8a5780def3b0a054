#pragma once
// The bus floor: what the transport alone costs between two processes on the pipeline's kind
// of bus, measured in the same run as the pipeline so that a slow machine and a slow pipeline
// can be told apart (issue 54). A ping of a cloud's size and one of a pose's size go to
// relplane-bus-echo, which answers each with a pose-sized reply.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "latency_table.hpp"

namespace relplane::bench {

inline const std::string kFloorPing = "FLOOR_PING";
inline const std::string kFloorPong = "FLOOR_PONG";
// A reply's size: an encoded pose_t is about this large.
constexpr size_t kFloorReplyBytes = 200;

// Round trips of one run of the floor, milliseconds.
struct BusFloor {
  LatencySummary cloud_round_trip;  // a cloud out, a pose-sized reply back
  LatencySummary pose_round_trip;   // a pose-sized message out and back
  // The pipeline's three hops (cloud to the segmenter, planes to the mapper, pose back) on the
  // bare bus: one cloud round trip and half a pose round trip, at the median.
  double PipelineFloorMs() const;
  bool Valid() const { return cloud_round_trip.count > 0 && pose_round_trip.count > 0; }
};

// `value` / `floor`, or -1 when either is not a positive figure.
double RatioToFloor(double value, double floor);

// A ping's payload: `size` bytes (at least 8), the sequence number in the first 8.
std::vector<uint8_t> MakePing(int64_t seq, size_t size);
// The sequence number at the head of a ping or its reply; -1 when too short.
int64_t PingSeq(const uint8_t* data, size_t size);

}  // namespace relplane::bench
