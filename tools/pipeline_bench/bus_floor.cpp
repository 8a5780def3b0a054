#include "bus_floor.hpp"

#include <algorithm>
#include <cstring>

namespace relplane::bench {

double BusFloor::PipelineFloorMs() const {
  if (!Valid()) return -1.0;
  return cloud_round_trip.p50_ms + 0.5 * pose_round_trip.p50_ms;
}

double RatioToFloor(double value, double floor) {
  return value > 0.0 && floor > 0.0 ? value / floor : -1.0;
}

std::vector<uint8_t> MakePing(int64_t seq, size_t size) {
  std::vector<uint8_t> ping(std::max(size, sizeof seq), 0);
  std::memcpy(ping.data(), &seq, sizeof seq);
  return ping;
}

int64_t PingSeq(const uint8_t* data, size_t size) {
  int64_t seq = -1;
  if (size >= sizeof seq) std::memcpy(&seq, data, sizeof seq);
  return seq;
}

}  // namespace relplane::bench
