#include "intrinsics_flags.hpp"

#include <fstream>

namespace relplane::tum {

void AddIntrinsicsFlags(cli::Parser& parser, IntrinsicsFlags* flags) {
  parser.Add("--calibration", &flags->calibration,
             "file with 'fx fy cx cy [depth_scale]' (default: the folder's calibration.txt, "
             "else TUM's 525 525 319.5 239.5 5000)");
  parser.Add("--fx", &flags->fx, "focal length in x, pixels").Positive();
  parser.Add("--fy", &flags->fy, "focal length in y, pixels").Positive();
  parser.Add("--cx", &flags->cx, "principal point x, pixels").NonNegative();
  parser.Add("--cy", &flags->cy, "principal point y, pixels").NonNegative();
  parser.Add("--depth-scale", &flags->depth_scale, "PNG value per metre (TUM: 5000)").Positive();
}

Intrinsics ResolveIntrinsics(const IntrinsicsFlags& flags, const std::string& folder_calibration) {
  Intrinsics k;
  if (!flags.calibration.empty()) {
    k = ReadCalibration(flags.calibration);
  } else if (!folder_calibration.empty() && std::ifstream(folder_calibration).good()) {
    k = ReadCalibration(folder_calibration);
  }
  if (flags.fx > 0.0) k.fx = flags.fx;
  if (flags.fy > 0.0) k.fy = flags.fy;
  if (flags.cx >= 0.0) k.cx = flags.cx;
  if (flags.cy >= 0.0) k.cy = flags.cy;
  if (flags.depth_scale > 0.0) k.depth_scale = flags.depth_scale;
  return k;
}

}  // namespace relplane::tum
