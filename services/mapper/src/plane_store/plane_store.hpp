#pragma once
// The rltplanes (§II.A), owned by registration: each plane's untransformed observations.

#include <cstdint>
#include <map>
#include <set>

#include "plane_store/rltplane.hpp"

namespace relplane::mapper {

struct PlaneStore {
  std::map<int64_t, RltPlane> planes;
  std::set<int64_t> recent;  // seen within the last-seen window (§II.A)
  int64_t next_id = 0;
  int64_t last_sweep = -1;  // iteration old observations were last dropped from every plane

  RltPlane* Plane(int64_t id) {
    auto it = planes.find(id);
    return it == planes.end() ? nullptr : &it->second;
  }
  // Rltplane `id` left the map (§II.F).
  void Forget(int64_t id) {
    recent.erase(id);
    planes.erase(id);
  }
  const RltPlane* Plane(int64_t id) const {
    auto it = planes.find(id);
    return it == planes.end() ? nullptr : &it->second;
  }
};

}  // namespace relplane::mapper
