#pragma once
// Reads PCD v0.7 point clouds (ascii, binary, binary_compressed) into flat x/y/z arrays.
// Only x, y and z are kept; other fields (rgba, normals, ...) are skipped by their size.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace relplane::pcd {

// Every reader failure; what() is one line naming the file and the problem.
class PcdError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct PcdCloud {
  int width = 0;         // points per row (= points for an unorganized cloud)
  int height = 0;        // rows (1 for an unorganized cloud)
  std::string encoding;  // "ascii", "binary" or "binary_compressed"
  // Coordinates in the file's own frame, row-major; invalid points stay NaN.
  std::vector<float> x, y, z;
  size_t size() const { return x.size(); }
};

// Parses the bytes of a PCD file; `name` stands in for the file name in messages.
PcdCloud ParsePcd(const std::string& bytes, const std::string& name);
// Reads and parses one file.
PcdCloud ReadPcd(const std::string& path);

// Optical frame (x right, y down, z forward) -> relplane sensor frame (x forward, y left,
// z up), in place: x' = z, y' = -x, z' = -y.
void OpticalToSensor(PcdCloud* cloud);

}  // namespace relplane::pcd
