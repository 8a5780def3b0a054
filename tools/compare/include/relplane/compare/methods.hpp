#pragma once
// The methods side by side, each run on one frame at a time with only its own work timed.

#include <string>
#include <vector>

#include "relplane/common/depth_camera.hpp"
#include "relplane/compare/detections.hpp"
#include "relplane/compare/organized_frame.hpp"
#include "relplane/compare/pcl_segmenters.hpp"
#include "relplane/segmenter/segmenter.hpp"

namespace relplane::compare {

struct MethodsOptions {
  // relplane's segmenter, with the camera's preset; keep_labels where truth is scored by the
  // points each plane holds (it then describes every point, not a subsample: slower).
  segmenter::Options relplane;
  camera::DepthCameraModel camera;  // the camera: SAC's distance threshold follows its noise
  OrganizedParams organized;
  SacParams sac;
  bool run_sac = true;
};

// One method's answer on one frame. For relplane, `detections.labels` index its input cloud;
// for PCL, the frame's pixels.
struct MethodRun {
  Detections detections;
  double seconds = 0.0;
};

class Methods {
 public:
  explicit Methods(const MethodsOptions& options);

  // The methods' names, in the order Run returns them.
  std::vector<std::string> Names() const;
  // Every method on one frame: relplane on `cloud` (its input as a stream gives it), PCL on
  // `grid` (the same points as an image).
  std::vector<MethodRun> Run(const segmenter::Cloud& cloud, const OrganizedFrame& grid);

 private:
  MethodsOptions options_;
  segmenter::Segmenter stream_;  // seeded by the frame before, as the service runs
  segmenter::Segmenter alone_;   // reset before every frame, as PCL's methods run
};

// RANSAC's single distance threshold for a frame: three times the noise the camera resolves at
// the frame's median depth, and never below 2 cm (PCL's tutorials' value at 1-2 m).
double SacThreshold(const camera::DepthCameraModel& camera, const OrganizedFrame& grid);

}  // namespace relplane::compare
