#pragma once
// Precision, recall and errors of detected planes against truth, summed over frames.

#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <vector>

namespace relplane::plane_truth {

// The angle between two planes with normals a and b, whichever way each points, degrees (atan2
// of sine and cosine: acos loses angles below ~0.01 degrees to rounding).
double PlaneAngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

struct Accuracy {
  int frames = 0;
  int true_planes = 0;  // true planes in view, summed over frames
  int recalled = 0;     // of them, matched by a detection
  int detected = 0;
  int correct = 0;                // detections that match some true plane
  double median_angle_deg = 0.0;  // over recalled true planes
  double median_offset_m = 0.0;
  // With a camera model: the smallest ratio of a detection's RMS to the noise the camera
  // resolves along its normal at its centroid (infinity without one).
  double min_rms_to_camera = std::numeric_limits<double>::infinity();
  // The largest angle between a detection's normal and the ray to its centroid, degrees: a
  // camera returns no depth beyond its incidence limit, so no surface is seen beyond it.
  double max_incidence_deg = 0.0;
  double Precision() const { return detected ? static_cast<double>(correct) / detected : 1.0; }
  double Recall() const { return true_planes ? static_cast<double>(recalled) / true_planes : 1.0; }
};

// Collects matches frame by frame; Summary() gives the medians.
class AccuracyTally {
 public:
  void AddFrame() { ++acc_.frames; }
  void AddDetections(int detected, int correct) {
    acc_.detected += detected;
    acc_.correct += correct;
  }
  void AddMissed() { ++acc_.true_planes; }
  void AddRecalled(double angle_deg, double offset_m);
  void AddRmsToCamera(double ratio) { rms_ratios_.push_back(ratio); }
  void AddIncidence(double deg) { acc_.max_incidence_deg = std::max(acc_.max_incidence_deg, deg); }
  Accuracy Summary() const;

 private:
  Accuracy acc_;
  std::vector<double> angles_, offsets_, rms_ratios_;
};

}  // namespace relplane::plane_truth
