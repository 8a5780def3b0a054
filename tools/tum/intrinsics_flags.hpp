#pragma once
// The command line's way to give a depth image's intrinsics: a calibration file, or any of
// --fx --fy --cx --cy --depth-scale over TUM's defaults (both: the flags win).

#include <string>

#include "relplane/common/cli.hpp"
#include "relplane/tum/tum_folder.hpp"

namespace relplane::tum {

struct IntrinsicsFlags {
  std::string calibration;
  double fx = 0.0, fy = 0.0, cx = -1.0, cy = -1.0, depth_scale = 0.0;  // unset
};

void AddIntrinsicsFlags(cli::Parser& parser, IntrinsicsFlags* flags);
// The intrinsics the flags give; `folder_calibration` is read when no file was named and it
// exists (a folder's own calibration.txt). Throws DepthImageError for a bad file.
Intrinsics ResolveIntrinsics(const IntrinsicsFlags& flags,
                             const std::string& folder_calibration = "");

}  // namespace relplane::tum
