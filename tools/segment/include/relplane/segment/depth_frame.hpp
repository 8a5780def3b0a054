#pragma once
// Depth frames read from files for relplane-segment. The reader is chosen by the file's type
// (ReadDepthFrame); each reader is one function returning a DepthFrame in the sensor frame.

#include <stdexcept>
#include <string>
#include <vector>

namespace relplane::segment {

// Every reader failure; what() is one line naming the file and the problem.
class FrameError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One frame's points, metres, relplane's sensor frame (x forward, y left, z up), row-major;
// invalid points NaN.
struct DepthFrame {
  std::string name;  // the file name without its folder
  int width = 0;     // points per row (all points for an unorganized cloud)
  int height = 0;    // rows (1 for an unorganized cloud)
  std::vector<float> x, y, z;
  bool Organized() const { return height > 1; }
};

struct ReadOptions {
  bool optical = false;  // the file is in the optical frame (x right, y down, z forward)
};

// The file types ReadDepthFrame knows, as extensions (".pcd").
const std::vector<std::string>& KnownFrameTypes();

// Reads one frame with the reader for its file type; throws FrameError.
DepthFrame ReadDepthFrame(const std::string& path, const ReadOptions& options);

}  // namespace relplane::segment
