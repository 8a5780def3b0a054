#pragma once
// Real frames with hand-labelled truth: the PCD frames of a folder and the labels beside them.

#include <stdexcept>
#include <string>
#include <vector>

#include "relplane/pcd/pcd_reader.hpp"
#include "relplane/plane_truth/labelled_planes.hpp"

namespace relplane::compare {

struct LabelledFrame {
  std::string name;     // the file's stem
  pcd::PcdCloud cloud;  // organized, in the sensor frame
  std::vector<plane_truth::Label> labels;
};

// Every NAME.json in `labels_dir` (sorted) with NAME.pcd from `frames_dir`, an organized frame
// in the camera's optical frame. Throws std::runtime_error, one line, for a missing folder or
// frame, or a file that does not parse.
std::vector<LabelledFrame> LoadLabelledFrames(const std::string& frames_dir,
                                              const std::string& labels_dir);

}  // namespace relplane::compare
