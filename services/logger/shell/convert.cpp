#include "convert.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <relplane/plane_set_t.hpp>

#include "relplane/common/bus.hpp"
#include "relplane/common/covariance.hpp"

namespace relplane::eval {
namespace {

bool Finite(const float* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

Eigen::Vector3d Vec(const float v[3]) { return {v[0], v[1], v[2]}; }

}  // namespace

bool FromMessage(const relplane::pose_t& msg, PoseSample* out, std::string* reason) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(msg.position[i])) {
      *reason = "pose seq " + std::to_string(msg.seq) + ": non-finite position";
      return false;
    }
  }
  const Eigen::Quaterniond q(msg.orientation[0], msg.orientation[1], msg.orientation[2],
                             msg.orientation[3]);
  const double norm = q.norm();
  if (!std::isfinite(norm) || norm < 1e-9) {
    *reason = "pose seq " + std::to_string(msg.seq) + ": invalid orientation quaternion";
    return false;
  }
  std::string why_covariance;
  out->utime = msg.utime;
  out->seq = msg.seq;
  out->position = {msg.position[0], msg.position[1], msg.position[2]};
  out->orientation = q.normalized();
  if (!geometry::ValidCovariance(msg.covariance, &why_covariance)) {
    *reason = "pose seq " + std::to_string(msg.seq) + ": " + why_covariance;
    return false;
  }
  out->status = msg.status;
  out->covariance = geometry::CovarianceFromRowMajor(msg.covariance);
  return true;
}

bool FromMessage(const relplane::map_t& msg, MapSnapshot* out, std::string* reason) {
  out->utime = msg.utime;
  out->seq = msg.seq;
  out->planes.clear();
  out->groups.clear();
  for (const relplane::plane_t& p : msg.planes) {
    bool ok = Finite(p.normal, 3) && std::isfinite(p.d) && Finite(p.centroid, 3);
    for (const auto& v : p.vertices) ok = ok && v.size() == 3 && Finite(v.data(), 3);
    if (!ok) {
      *reason = "map seq " + std::to_string(msg.seq) + ": plane " + std::to_string(p.id) +
                " has non-finite numbers";
      return false;
    }
    PlaneRecord r;
    r.id = p.id;
    r.normal = Vec(p.normal);
    r.d = p.d;
    r.centroid = Vec(p.centroid);
    for (const auto& v : p.vertices) r.vertices.emplace_back(v[0], v[1], v[2]);
    r.observations = p.num_points;
    r.rms = p.rms;
    out->planes.push_back(std::move(r));
  }
  for (const relplane::group_t& g : msg.groups) {
    out->groups.push_back({g.id, g.basis_id, g.members});
  }
  return true;
}

StatusSample FromMessage(const relplane::status_t& msg) {
  StatusSample s;
  s.utime = msg.utime;
  s.service = msg.service;
  s.frames_processed = msg.frames_processed;
  s.frames_dropped = msg.frames_dropped;
  s.inputs_rejected = msg.inputs_rejected;
  // float on the wire: round to 0.1 us so 0.01 ms does not print as 0.00999999978.
  const auto ms = [](float v) { return std::round(static_cast<double>(v) * 1e4) * 1e-4; };
  s.p50_ms = ms(msg.p50_ms);
  s.p99_ms = ms(msg.p99_ms);
  s.max_ms = ms(msg.max_ms);
  s.last_seq = msg.last_seq;
  return s;
}

const std::vector<std::string>& RecordedChannels() {
  static const std::vector<std::string> channels = {"POSE",      "SIM_TRUTH", "MAP",
                                                    "SIM_WORLD", "STATUS",    "PLANES"};
  return channels;
}

FeedResult FeedEncoded(RunRecorder& recorder, const std::string& channel, const uint8_t* data,
                       size_t size, int64_t receive_us, std::string* reason) {
  const auto rejected = [&](const std::string& why) {
    *reason = channel + ": " + why;
    return FeedResult::kRejected;
  };
  std::string why;
  if (channel == "POSE" || channel == "SIM_TRUTH") {
    relplane::pose_t msg;
    PoseSample pose;
    if (!bus::Decode(data, size, &msg, &why) || !FromMessage(msg, &pose, &why)) {
      return rejected(why);
    }
    if (channel == "POSE") {
      recorder.OnPose(pose, receive_us);
    } else {
      recorder.OnTruth(pose, receive_us);
    }
    return FeedResult::kUsed;
  }
  if (channel == "MAP" || channel == "SIM_WORLD") {
    relplane::map_t msg;
    MapSnapshot map;
    if (!bus::Decode(data, size, &msg, &why) || !FromMessage(msg, &map, &why)) {
      return rejected(why);
    }
    if (channel == "MAP") {
      recorder.OnMap(std::move(map), receive_us);
    } else {
      recorder.OnWorld(std::move(map), receive_us);
    }
    return FeedResult::kUsed;
  }
  if (channel == "STATUS") {
    relplane::status_t msg;
    if (!bus::Decode(data, size, &msg, &why)) return rejected(why);
    // Counters are summed over services: a hostile value must not overflow the sum (found by
    // relplane-fuzz-logger). 2^40 frames is 1,000 years at 30 Hz.
    constexpr int64_t kMaxCounter = int64_t{1} << 40;
    for (const int64_t counter : {msg.frames_processed, msg.frames_dropped, msg.inputs_rejected}) {
      if (counter < 0 || counter > kMaxCounter) {
        return rejected("counter " + std::to_string(counter) + " out of range");
      }
    }
    // The name is printed in the summary and keys a table: no control characters (a hostile
    // name could drive the terminal) and a bounded length.
    const bool name_ok =
        !msg.service.empty() && msg.service.size() <= 64 &&
        std::all_of(msg.service.begin(), msg.service.end(), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
        });
    if (!name_ok) return rejected("service name is not 1-64 characters of [A-Za-z0-9._-]");
    recorder.OnStatus(FromMessage(msg), receive_us);
    return FeedResult::kUsed;
  }
  if (channel == "PLANES") {
    relplane::plane_set_t msg;
    if (!bus::Decode(data, size, &msg, &why)) return rejected(why);
    recorder.OnPlanes(msg.seq, receive_us);
    return FeedResult::kUsed;
  }
  return FeedResult::kIgnored;
}

}  // namespace relplane::eval
