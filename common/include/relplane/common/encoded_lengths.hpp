#pragma once
// Walks an encoded relplane message and checks every declared array length against the bytes
// that are really there, before lcm-gen's decoder sees it. The generated decoder resizes each
// array to the declared length first and multiplies that length in a 32-bit int, so a hostile
// length means a multi-gigabyte allocation or a read past the buffer.

#include <cstddef>
#include <cstdint>
#include <string>

namespace relplane {
struct point_cloud_t;
struct plane_set_t;
struct map_t;
struct status_t;
}  // namespace relplane

namespace relplane::bus {

// Types without variable-length arrays of their own need no walk.
template <class M>
bool CheckEncodedLengths(const M*, const uint8_t*, size_t, std::string*) {
  return true;
}

bool CheckEncodedLengths(const point_cloud_t*, const uint8_t* data, size_t size,
                         std::string* reason);
bool CheckEncodedLengths(const plane_set_t*, const uint8_t* data, size_t size,
                         std::string* reason);
bool CheckEncodedLengths(const map_t*, const uint8_t* data, size_t size, std::string* reason);
// Strings: lcm-gen subtracts one from the declared length without checking it is positive.
bool CheckEncodedLengths(const status_t*, const uint8_t* data, size_t size, std::string* reason);

}  // namespace relplane::bus
