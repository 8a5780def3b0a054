#pragma once
// The bus behind a small interface (STYLE.md "Seams for testing"): services publish and
// subscribe typed lcm-gen messages through it; tests can run it on memq://.
// This header does not include LCM; only lcm_bus.cpp does.

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "relplane/common/encoded_lengths.hpp"

namespace relplane::bus {

class Bus {
 public:
  using RawHandler = std::function<void(const std::string& channel, const uint8_t* data, size_t size)>;

  virtual ~Bus() = default;
  // Sends one encoded message; false when the transport refused it.
  virtual bool PublishRaw(const std::string& channel, const uint8_t* data, size_t size) = 0;
  // Calls `handler` for every message on `channel` (exact name). `queue_capacity` is how many
  // messages may wait undelivered before the transport drops the oldest.
  virtual void SubscribeRaw(const std::string& channel, RawHandler handler, int queue_capacity) = 0;
  // Delivers pending messages, waiting at most `timeout_ms` for the first.
  // Returns > 0 when a message was handled, 0 on time-out, < 0 on a transport error.
  virtual int Handle(int timeout_ms) = 0;
  // The URL the bus was opened with.
  virtual const std::string& Url() const = 0;
};

// The URL to use: `flag` when given, else $LCM_DEFAULT_URL, else "" (LCM's own default).
std::string ResolveUrl(const std::string& flag);
// The URL of the cloud bus, which carries SENSOR_POINTS alone: `flag` when given, else the
// main bus's URL. On udpm every process bound to a port reads every datagram sent to it, so
// clouds on a port of their own are read only by the processes that use them.
std::string ResolveCloudUrl(const std::string& flag, const std::string& main_url);
// Opens an LCM bus; throws std::runtime_error with a one-line reason when it cannot.
std::unique_ptr<Bus> OpenLcmBus(const std::string& url);

// Default receive queue: deep enough that a burst replayed faster than real time is kept.
constexpr int kDefaultQueueCapacity = 1000;
// Messages larger than this are refused before decoding (a 640x480 cloud is ~3.7 MB).
constexpr size_t kDefaultMaxMessageBytes = 64u << 20;

template <class M>
bool Publish(Bus& bus, const std::string& channel, const M& message) {
  const int size = message.getEncodedSize();
  if (size < 0) return false;
  // One buffer per thread and type, grown to the largest message: no allocation per message.
  thread_local std::vector<uint8_t> buffer;
  if (buffer.size() < static_cast<size_t>(size)) buffer.resize(static_cast<size_t>(size));
  if (message.encode(buffer.data(), 0, size) != size) return false;
  return bus.PublishRaw(channel, buffer.data(), static_cast<size_t>(size));
}

// Decodes one message defensively: a wrong fingerprint, truncation, trailing bytes, an absurd
// array length or an oversize buffer is a reason string, never an exception or a crash.
template <class M>
bool Decode(const uint8_t* data, size_t size, M* out, std::string* reason,
            size_t max_bytes = kDefaultMaxMessageBytes) {
  if (size > max_bytes) {
    *reason = "message of " + std::to_string(size) + " bytes exceeds the limit";
    return false;
  }
  if (size > static_cast<size_t>(std::numeric_limits<int>::max())) {
    *reason = "message too large to decode";
    return false;
  }
  if (!CheckEncodedLengths(static_cast<const M*>(nullptr), data, size, reason)) {
    *reason = "undecodable: " + *reason;
    return false;
  }
  try {
    const int used = out->decode(data, 0, static_cast<int>(size));
    if (used < 0) {
      *reason = "undecodable: wrong type fingerprint or truncated";
      return false;
    }
    if (static_cast<size_t>(used) != size) {
      *reason = "undecodable: " + std::to_string(size - used) + " trailing bytes";
      return false;
    }
  } catch (const std::exception& e) {
    // lcm-gen code resizes arrays to the lengths the message declares before reading them.
    *reason = std::string("undecodable: absurd array length (") + e.what() + ")";
    return false;
  }
  return true;
}

// Readies a message kept from one delivery to the next for decoding. lcm-gen's decoder leaves an
// array untouched when its declared length is 0, so the previous message's elements would stay:
// by default a fresh message; a point cloud (the one large message) has its arrays emptied,
// keeping their capacity.
template <class M>
void ResetForDecode(M* message) {
  *message = M();
}
void ResetForDecode(point_cloud_t* message);

// Typed subscription: `on_message` gets each decoded message; `on_reject` gets the reason for
// every message that could not be decoded. Messages are decoded into one object kept by the
// subscription (ResetForDecode: a cloud's arrays keep their capacity, so no allocation per
// cloud in steady state): `on_message` may modify it (e.g. swap its arrays out) but must not
// keep a reference to it.
template <class M>
void Subscribe(Bus& bus, const std::string& channel, std::function<void(M&)> on_message,
               std::function<void(const std::string& reason)> on_reject,
               int queue_capacity = kDefaultQueueCapacity,
               size_t max_bytes = kDefaultMaxMessageBytes) {
  bus.SubscribeRaw(
      channel,
      [on_message = std::move(on_message), on_reject = std::move(on_reject), max_bytes,
       message = std::make_shared<M>()](const std::string&, const uint8_t* data, size_t size) {
        std::string reason;
        ResetForDecode(message.get());
        if (Decode(data, size, message.get(), &reason, max_bytes)) {
          on_message(*message);
        } else {
          on_reject(reason);
        }
      },
      queue_capacity);
}

}  // namespace relplane::bus
