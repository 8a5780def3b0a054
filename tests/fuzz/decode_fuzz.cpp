// libFuzzer target for the bus decode-and-validate path every service uses (bus::Decode).
// Input: one selector byte, then the message bytes. When the selector's high bit is set the
// type's real fingerprint is put in front, so the fuzzer explores message bodies instead of
// spending its time guessing 64-bit hashes.

#include <relplane/map_t.hpp>
#include <relplane/odometry_t.hpp>
#include <relplane/plane_set_t.hpp>
#include <relplane/point_cloud_t.hpp>
#include <relplane/pose_t.hpp>
#include <relplane/status_t.hpp>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "relplane/common/bus.hpp"

namespace {

template <class M>
void Exercise(const uint8_t* data, size_t size, bool with_hash) {
  std::vector<uint8_t> buf;
  if (with_hash) {
    const int64_t hash = M::getHash();
    for (int i = 7; i >= 0; --i) buf.push_back(static_cast<uint8_t>(hash >> (8 * i)));
  }
  buf.insert(buf.end(), data, data + size);
  M message;
  std::string reason;
  if (!relplane::bus::Decode(buf.data(), buf.size(), &message, &reason)) return;
  // What decodes must encode back to the same bytes.
  std::vector<uint8_t> again(static_cast<size_t>(message.getEncodedSize()));
  if (message.encode(again.data(), 0, static_cast<int>(again.size())) != static_cast<int>(again.size()) ||
      again != buf) {
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t selector = data[0];
  const bool with_hash = (selector & 0x80) != 0;
  ++data;
  --size;
  switch (selector & 0x7f) {
    case 0: Exercise<relplane::point_cloud_t>(data, size, with_hash); break;
    case 1: Exercise<relplane::plane_set_t>(data, size, with_hash); break;
    case 2: Exercise<relplane::map_t>(data, size, with_hash); break;
    case 3: Exercise<relplane::pose_t>(data, size, with_hash); break;
    case 5: Exercise<relplane::odometry_t>(data, size, with_hash); break;
    default: Exercise<relplane::status_t>(data, size, with_hash); break;
  }
  return 0;
}
