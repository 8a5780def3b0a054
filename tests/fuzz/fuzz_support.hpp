#pragma once
// Shared by the per-service fuzzers: an in-memory bus that hands fuzzed bytes to a service's
// real subscription (bus::Subscribe: size check, defensive Decode, validation) and keeps what
// it publishes, and helpers that turn fuzzer bytes into numbers, sometimes hostile ones.

#include <fuzzer/FuzzedDataProvider.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <relplane/plane_t.hpp>

#include "relplane/common/bus.hpp"

namespace relplane::fuzz {

class MemoryBus : public bus::Bus {
 public:
  bool PublishRaw(const std::string& channel, const uint8_t* data, size_t size) override {
    published[channel].emplace_back(data, data + size);
    return true;
  }
  void SubscribeRaw(const std::string& channel, RawHandler handler, int) override {
    handlers_[channel] = std::move(handler);
  }
  int Handle(int) override { return 0; }
  const std::string& Url() const override { return url_; }

  // Delivers `bytes` to the subscriber of `channel`, as the transport would.
  void Deliver(const std::string& channel, const std::vector<uint8_t>& bytes) {
    const auto it = handlers_.find(channel);
    if (it != handlers_.end()) it->second(channel, bytes.data(), bytes.size());
  }

  std::map<std::string, std::vector<std::vector<uint8_t>>> published;

 private:
  std::map<std::string, RawHandler> handlers_;
  std::string url_ = "memory://fuzz";
};

// The encoded bytes of `msg` (fingerprint first), as a publisher sends them.
template <class M>
std::vector<uint8_t> Encode(const M& msg) {
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// Mostly a number in [-range, range]; now and then NaN, an infinity, a huge or a tiny one.
inline double Number(FuzzedDataProvider& in, double range) {
  switch (in.ConsumeIntegralInRange<int>(0, 15)) {
    case 0:
      return std::numeric_limits<double>::quiet_NaN();
    case 1:
      return std::numeric_limits<double>::infinity() * (in.ConsumeBool() ? 1 : -1);
    case 2:
      return in.ConsumeFloatingPoint<double>();
    case 3:
      return 0.0;
    default:
      return in.ConsumeFloatingPointInRange<double>(-range, range);
  }
}

// A published message must decode, and what a service publishes must be finite: NaN or inf
// going out means bad input got through a validation.
template <class M>
M MustDecode(const std::vector<uint8_t>& bytes) {
  M msg;
  std::string reason;
  if (!bus::Decode(bytes.data(), bytes.size(), &msg, &reason)) std::abort();
  return msg;
}

inline void MustBeFinite(double value) {
  if (!std::isfinite(value)) std::abort();
}

// Every number a published plane carries is finite.
inline void MustBeFinite(const plane_t& plane) {
  for (float v : plane.normal) MustBeFinite(v);
  for (float v : plane.centroid) MustBeFinite(v);
  MustBeFinite(plane.d);
  MustBeFinite(plane.rms);
  for (const auto& vertex : plane.vertices) {
    for (float v : vertex) MustBeFinite(v);
  }
}

}  // namespace relplane::fuzz
