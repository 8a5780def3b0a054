#pragma once
// 16-bit greyscale PNG depth images (the TUM RGB-D and ICL-NUIM convention: one unsigned value
// per pixel, 0 where nothing was measured), read and written with libpng.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace relplane::tum {

// Every reading or writing failure; what() is one line naming the file and the problem.
class DepthImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<uint16_t> values;  // row-major, top row first; 0: no measurement
  uint16_t At(int u, int v) const { return values[static_cast<size_t>(v) * width + u]; }
};

// Reads a 16-bit (or 8-bit) single-channel PNG. Anything else (colour, alpha, palette) is an
// error: a depth image has one channel.
DepthImage ReadDepthPng(const std::string& path);
// Writes a 16-bit single-channel PNG.
void WriteDepthPng(const std::string& path, const DepthImage& image);

}  // namespace relplane::tum
