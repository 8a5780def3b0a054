#pragma once
// Detected planes against hand-labelled truth for real organized frames
// (tests/segmenter/data/kinect_truth/*.json: each plane a person sees, boxes of pixels inside
// it, and its least-squares fit, in relplane's sensor frame). A detection is the labelled plane
// when it holds most of the label's points and lies along it.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "relplane/pcd/pcd_reader.hpp"
#include "relplane/plane_truth/accuracy.hpp"
#include "relplane/segmenter/cloud.hpp"

namespace relplane::plane_truth {

struct Label {
  std::string name;
  Eigen::Vector3d normal;
  double d = 0.0;
  std::vector<size_t> pixels;  // finite points of its boxes, indices into the frame
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};

// The labels of one frame (`cloud`: the frame, organized, in the labels' frame). Throws
// YAML::Exception for an unreadable file, std::out_of_range for a box outside the frame.
std::vector<Label> LoadLabels(const std::string& file, const pcd::PcdCloud& cloud);

// One frame's detections against its labels.
struct LabelScore {
  int labels = 0;
  int found = 0;  // labels held by one detection along them
  int split = 0;  // labels with two or more detections along them
  int detected = 0;
  std::vector<int> unmatched;  // indices of the detections that are no label's
  std::vector<std::string> missed;
  std::vector<double> angles_deg, offsets_m;  // per found label: its detection's errors
};

// `point_labels`: per point of the frame, the index of its detection in `planes` or -1.
LabelScore ScoreLabels(const std::vector<Label>& labels,
                       const std::vector<segmenter::DetectedPlane>& planes,
                       const std::vector<int32_t>& point_labels);

// Adds one frame's score to a tally: labels are the true planes, claimed detections the correct.
void Tally(const LabelScore& score, AccuracyTally* tally);

}  // namespace relplane::plane_truth
