#include <relplane/plane_set_t.hpp>
#include <stdexcept>

#include "convert.hpp"  // the mapper service's
#include "options_yaml.hpp"
#include "process_cpu.hpp"
#include "relplane/mapper/mapper.hpp"
#include "stage_profile.hpp"

namespace relplane::bench {

std::vector<double> ProfileMapper(const std::string& scenario,
                                  const std::vector<std::vector<uint8_t>>& plane_sets) {
  mapper::Mapper map(mapper::LoadMapperOptions(scenario));
  std::vector<double> ms;
  for (size_t k = 0; k < plane_sets.size(); ++k) {
    plane_set_t msg;
    std::vector<mapper::PlaneInput> planes;
    std::string reason = "does not decode";
    if (msg.decode(plane_sets[k].data(), 0, static_cast<int>(plane_sets[k].size())) < 0 ||
        !mapper::FromPlaneSet(msg, &planes, &reason)) {
      throw std::runtime_error("plane set " + std::to_string(k) + ": " + reason);
    }
    const double t0 = ThreadCpuMs();
    map.Process(msg.seq, planes);
    ms.push_back(ThreadCpuMs() - t0);
  }
  return ms;
}

}  // namespace relplane::bench
