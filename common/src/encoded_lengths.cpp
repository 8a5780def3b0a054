#include "relplane/common/encoded_lengths.hpp"

#include <relplane/point_cloud_t.hpp>

namespace relplane::bus {
namespace {

// A cursor over big-endian LCM encoding that fails instead of reading past the end.
class Cursor {
 public:
  Cursor(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  bool Skip(size_t n) {
    if (n > size_ - pos_) return false;
    pos_ += n;
    return true;
  }
  // The next `n` bytes (which must be there: check with a length read first).
  const uint8_t* Peek() const { return data_ + pos_; }
  bool ReadInt32(int32_t* v) {
    if (size_ - pos_ < 4) return false;
    const uint32_t u = (uint32_t{data_[pos_]} << 24) | (uint32_t{data_[pos_ + 1]} << 16) |
                       (uint32_t{data_[pos_ + 2]} << 8) | uint32_t{data_[pos_ + 3]};
    pos_ += 4;
    *v = static_cast<int32_t>(u);
    return true;
  }
  // Reads an array length and checks that `count * element_bytes` bytes follow.
  bool ReadLength(size_t element_bytes, int32_t* count, std::string* reason, const char* what) {
    if (!ReadInt32(count)) return Fail(reason, "truncated before the length of ", what);
    if (*count < 0) return Fail(reason, "negative length of ", what);
    if (static_cast<size_t>(*count) > (size_ - pos_) / element_bytes) {
      return Fail(reason, "declared length exceeds the message for ", what);
    }
    return true;
  }
  static bool Fail(std::string* reason, const char* text, const char* what) {
    *reason = std::string(text) + what;
    return false;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

constexpr size_t kHash = 8;

bool WalkPlane(Cursor& c, std::string* reason) {
  // id, normal[3], d, centroid[3]
  if (!c.Skip(8 + 12 + 4 + 12)) return Cursor::Fail(reason, "truncated ", "plane_t");
  int32_t vertices = 0;
  if (!c.ReadLength(12, &vertices, reason, "plane_t.vertices")) return false;
  if (!c.Skip(12 * static_cast<size_t>(vertices) + 4 + 4)) {
    return Cursor::Fail(reason, "truncated ", "plane_t");
  }
  return true;
}

// Smallest encoded plane_t: no vertices.
constexpr size_t kMinPlaneBytes = 8 + 12 + 4 + 12 + 4 + 4 + 4;

bool WalkPlanes(Cursor& c, std::string* reason) {
  int32_t planes = 0;
  if (!c.ReadLength(kMinPlaneBytes, &planes, reason, "planes")) return false;
  for (int32_t i = 0; i < planes; ++i) {
    if (!WalkPlane(c, reason)) return false;
  }
  return true;
}

bool WalkString(Cursor& c, std::string* reason, const char* what) {
  int32_t length = 0;
  if (!c.ReadLength(1, &length, reason, what)) return false;
  // Encoded LCM strings carry their terminating NUL, so the length is at least one.
  if (length < 1) return Cursor::Fail(reason, "zero length of ", what);
  // lcm-gen encodes up to the first NUL but sizes by std::string::size(), so a string with an
  // inner NUL or no terminator would not encode back to what was received: refuse it.
  const uint8_t* bytes = c.Peek();
  for (int32_t i = 0; i + 1 < length; ++i) {
    if (bytes[i] == 0) return Cursor::Fail(reason, "NUL inside ", what);
  }
  if (bytes[length - 1] != 0) return Cursor::Fail(reason, "no terminating NUL in ", what);
  return c.Skip(static_cast<size_t>(length));
}

}  // namespace

bool CheckEncodedLengths(const status_t*, const uint8_t* data, size_t size, std::string* reason) {
  Cursor c(data, size);
  if (!c.Skip(kHash + 8)) return Cursor::Fail(reason, "truncated ", "status_t");
  if (!WalkString(c, reason, "status_t.service")) return false;
  // frames_processed, frames_dropped, inputs_rejected, p50/p99/max, last_seq
  if (!c.Skip(8 * 3 + 4 * 3 + 8)) return Cursor::Fail(reason, "truncated ", "status_t");
  return WalkString(c, reason, "status_t.detail");
}

bool CheckEncodedLengths(const point_cloud_t*, const uint8_t* data, size_t size,
                         std::string* reason) {
  Cursor c(data, size);
  int32_t points = 0;
  if (!c.Skip(kHash + 8 + 8)) return Cursor::Fail(reason, "truncated ", "point_cloud_t");
  // x, y and z: three floats per point.
  return c.ReadLength(12, &points, reason, "point_cloud_t points");
}

bool CheckEncodedLengths(const plane_set_t*, const uint8_t* data, size_t size,
                         std::string* reason) {
  Cursor c(data, size);
  if (!c.Skip(kHash + 8 + 8)) return Cursor::Fail(reason, "truncated ", "plane_set_t");
  return WalkPlanes(c, reason);
}

bool CheckEncodedLengths(const map_t*, const uint8_t* data, size_t size, std::string* reason) {
  Cursor c(data, size);
  if (!c.Skip(kHash + 8 + 8)) return Cursor::Fail(reason, "truncated ", "map_t");
  if (!WalkPlanes(c, reason)) return false;
  int32_t groups = 0;
  constexpr size_t kMinGroupBytes = 8 + 8 + 4;
  if (!c.ReadLength(kMinGroupBytes, &groups, reason, "groups")) return false;
  for (int32_t i = 0; i < groups; ++i) {
    int32_t members = 0;
    if (!c.Skip(16)) return Cursor::Fail(reason, "truncated ", "group_t");
    if (!c.ReadLength(8, &members, reason, "group_t.members")) return false;
    if (!c.Skip(8 * static_cast<size_t>(members))) {
      return Cursor::Fail(reason, "truncated ", "group_t");
    }
  }
  return true;
}

void ResetForDecode(point_cloud_t* message) {
  message->num_points = 0;
  message->x.clear();
  message->y.clear();
  message->z.clear();
}

}  // namespace relplane::bus
