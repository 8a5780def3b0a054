#include <relplane/plane_set_t.hpp>
#include <stdexcept>

#include "convert.hpp"  // the mapper service's
#include "options_yaml.hpp"
#include "process_cpu.hpp"
#include "relplane/mapper/mapper.hpp"
#include "relplane/mapper/pose_covariance.hpp"
#include "stage_profile.hpp"

namespace relplane::bench {
namespace {

template <typename Message>
void Encode(const Message& msg, std::vector<uint8_t>* buffer) {
  buffer->resize(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buffer->data(), 0, static_cast<int>(buffer->size()));
}

}  // namespace

std::vector<double> ProfileMapper(const std::string& scenario,
                                  const std::vector<std::vector<uint8_t>>& plane_sets) {
  mapper::Mapper map(mapper::LoadMapperOptions(scenario));
  std::vector<double> ms;
  std::vector<uint8_t> buffer;
  int64_t last_map_utime = -1;
  bool map_pending = false;
  for (size_t k = 0; k < plane_sets.size(); ++k) {
    plane_set_t msg;
    std::vector<mapper::PlaneInput> planes;
    std::string reason = "does not decode";
    if (msg.decode(plane_sets[k].data(), 0, static_cast<int>(plane_sets[k].size())) < 0 ||
        !mapper::FromPlaneSet(msg, &planes, &reason)) {
      throw std::runtime_error("plane set " + std::to_string(k) + ": " + reason);
    }
    // What the service computes per plane set besides receiving and sending: the pose, its
    // covariance and its message; the map and its message when it changed and is due.
    const double t0 = ThreadCpuMs();
    const mapper::PoseEstimate estimate = map.Process(msg.seq, planes);
    const pose_t pose = mapper::ToPoseMessage(estimate, mapper::ObservabilityOf(estimate).covariance,
                                              map.Height(), msg.utime, msg.seq);
    Encode(pose, &buffer);
    map_pending = map.TakeMapChanged() || map_pending;
    if (map_pending && (last_map_utime < 0 || msg.utime - last_map_utime >= mapper::kMapPeriodUs)) {
      Encode(mapper::ToMapMessage(map.Map(), msg.utime, msg.seq), &buffer);
      last_map_utime = msg.utime;
      map_pending = false;
    }
    ms.push_back(ThreadCpuMs() - t0);
  }
  return ms;
}

}  // namespace relplane::bench
