#pragma once
// The TUM RGB-D conventions for depth (Sturm et al., IROS 2012; ICL-NUIM follows them): a folder
// with `depth.txt` (one "timestamp filename" line per frame, '#' comments) and the 16-bit PNGs
// it names, depth = value / depth_scale metres along the optical axis (5000 per metre), and the
// pinhole intrinsics fx fy cx cy (pixels; pixel (u, v) has its centre at u, v).

#include <string>
#include <vector>

#include "relplane/pcd/pcd_reader.hpp"
#include "relplane/tum/depth_png.hpp"

namespace relplane::tum {

struct Intrinsics {
  double fx = 525.0;  // TUM's default for its Kinect recordings
  double fy = 525.0;
  double cx = 319.5;
  double cy = 239.5;
  double depth_scale = 5000.0;  // PNG value per metre
};

// A calibration file: "fx fy cx cy [depth_scale]" on its first line that is not empty or a '#'
// comment. Throws DepthImageError naming the file on anything else.
Intrinsics ReadCalibration(const std::string& path);
void WriteCalibration(const std::string& path, const Intrinsics& intrinsics);

struct DepthFrame {
  double timestamp = 0.0;  // seconds
  std::string path;        // the PNG, the folder joined to depth.txt's relative name
};

// FOLDER/depth.txt, in its order. Throws DepthImageError naming the line on a malformed one.
std::vector<DepthFrame> ReadDepthList(const std::string& folder);

// The depth image as an organized cloud (width x height, row-major) in relplane's sensor frame
// (x forward, y left, z up): pixel (u, v) with depth z is at (z, -(u - cx) z / fx,
// -(v - cy) z / fy); NaN where the value is 0.
pcd::PcdCloud DepthToCloud(const DepthImage& image, const Intrinsics& intrinsics);

}  // namespace relplane::tum
