#include "relplane/tum/tum_folder.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace relplane::tum {
namespace {

bool Blank(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

}  // namespace

Intrinsics ReadCalibration(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw DepthImageError(path + ": cannot open it");
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (Blank(line)) continue;
    std::istringstream fields(line);
    Intrinsics k;
    if (!(fields >> k.fx >> k.fy >> k.cx >> k.cy)) {
      throw DepthImageError(path + ":" + std::to_string(number) + ": expected fx fy cx cy [scale]");
    }
    double scale;
    if (fields >> scale) k.depth_scale = scale;
    std::string rest;
    if (fields >> rest) {
      throw DepthImageError(path + ":" + std::to_string(number) + ": unexpected '" + rest + "'");
    }
    if (!(k.fx > 0.0 && k.fy > 0.0 && k.depth_scale > 0.0 && std::isfinite(k.cx) &&
          std::isfinite(k.cy))) {
      throw DepthImageError(path + ":" + std::to_string(number) +
                            ": fx, fy and the scale must be positive");
    }
    return k;
  }
  throw DepthImageError(path + ": no calibration line (fx fy cx cy [scale])");
}

void WriteCalibration(const std::string& path, const Intrinsics& k) {
  std::ofstream out(path);
  out.precision(17);
  out << "# fx fy cx cy depth_scale (pixels; PNG value per metre)\n"
      << k.fx << ' ' << k.fy << ' ' << k.cx << ' ' << k.cy << ' ' << k.depth_scale << '\n';
  if (!out) throw DepthImageError(path + ": writing failed");
}

std::vector<DepthFrame> ReadDepthList(const std::string& folder) {
  const std::string list = folder + "/depth.txt";
  std::ifstream in(list);
  if (!in) throw DepthImageError(list + ": cannot open it");
  std::vector<DepthFrame> frames;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (Blank(line)) continue;
    std::istringstream fields(line);
    DepthFrame f;
    std::string name;
    if (!(fields >> f.timestamp >> name) || !std::isfinite(f.timestamp)) {
      throw DepthImageError(list + ":" + std::to_string(number) + ": expected 'timestamp file'");
    }
    f.path = folder + "/" + name;
    frames.push_back(f);
  }
  return frames;
}

pcd::PcdCloud DepthToCloud(const DepthImage& image, const Intrinsics& k) {
  pcd::PcdCloud cloud;
  cloud.width = image.width;
  cloud.height = image.height;
  cloud.encoding = "png";
  const size_t n = static_cast<size_t>(image.width) * image.height;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud.x.assign(n, nan);
  cloud.y.assign(n, nan);
  cloud.z.assign(n, nan);
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const size_t i = static_cast<size_t>(v) * image.width + u;
      if (image.values[i] == 0) continue;
      const double z = image.values[i] / k.depth_scale;
      cloud.x[i] = static_cast<float>(z);
      cloud.y[i] = static_cast<float>(-(u - k.cx) * z / k.fx);
      cloud.z[i] = static_cast<float>(-(v - k.cy) * z / k.fy);
    }
  }
  return cloud;
}

}  // namespace relplane::tum
