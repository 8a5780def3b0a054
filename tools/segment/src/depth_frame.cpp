#include "relplane/segment/depth_frame.hpp"

#include <algorithm>
#include <cctype>

#include "relplane/pcd/pcd_reader.hpp"

namespace relplane::segment {
namespace {

DepthFrame ReadPcdFrame(const std::string& path, const ReadOptions& options) {
  pcd::PcdCloud cloud;
  try {
    cloud = pcd::ReadPcd(path);
  } catch (const pcd::PcdError& e) {
    throw FrameError(e.what());
  }
  if (options.optical) pcd::OpticalToSensor(&cloud);
  DepthFrame frame;
  frame.width = cloud.width;
  frame.height = cloud.height;
  frame.x = std::move(cloud.x);
  frame.y = std::move(cloud.y);
  frame.z = std::move(cloud.z);
  return frame;
}

using Reader = DepthFrame (*)(const std::string&, const ReadOptions&);

struct FrameType {
  std::string extension;
  Reader read;
};

// One entry per file type; a new input format is a reader function and a line here.
const std::vector<FrameType>& FrameTypes() {
  static const std::vector<FrameType> types = {{".pcd", &ReadPcdFrame}};
  return types;
}

std::string LowerExtension(const std::string& name) {
  const size_t dot = name.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string extension = name.substr(dot);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace

const std::vector<std::string>& KnownFrameTypes() {
  static const std::vector<std::string> extensions = [] {
    std::vector<std::string> list;
    for (const FrameType& type : FrameTypes()) list.push_back(type.extension);
    return list;
  }();
  return extensions;
}

DepthFrame ReadDepthFrame(const std::string& path, const ReadOptions& options) {
  const std::string name = path.substr(path.find_last_of('/') + 1);
  const std::string extension = LowerExtension(name);
  for (const FrameType& type : FrameTypes()) {
    if (type.extension != extension) continue;
    DepthFrame frame = type.read(path, options);
    frame.name = name;
    return frame;
  }
  std::string known;
  for (const std::string& e : KnownFrameTypes()) known += (known.empty() ? "" : ", ") + e;
  throw FrameError(path + ": unknown file type (known: " + known + ")");
}

}  // namespace relplane::segment
