#pragma once
// PCL's plane segmentations on relplane's frames, behind a header without PCL: PCL's headers are
// slow to compile, so they stay in one source (pcl_segmenters.cpp).

#include <cstdint>
#include <vector>

#include "relplane/compare/organized_frame.hpp"

namespace relplane::compare {

// What a PCL segmentation found on a frame and how long PCL took (seconds of the calls into PCL
// only: the conversion of the frame to PCL's point type is not counted).
struct PclResult {
  std::vector<PlaneFit> planes;  // indices into the frame, planes in the sensor frame
  double seconds = 0.0;
};

// OrganizedMultiPlaneSegmentation on integral-image normals (Trevor et al. 2013, "Efficient
// organized point cloud segmentation with connected components"), the parameters explained
// where they are set.
struct OrganizedParams {
  bool covariance_normals = true;  // COVARIANCE_MATRIX; false: AVERAGE_3D_GRADIENT
  float max_depth_change = 0.02f;  // normals are not smoothed across depth jumps larger than this
  double normal_smoothing = 10.0;  // pixels
  unsigned min_inliers = 300;
  double angular_threshold_deg = 3.0;
  double distance_threshold = 0.02;  // metres
  double max_curvature = 0.001;      // PCL's default
};
PclResult SegmentOrganized(const OrganizedFrame& frame, const OrganizedParams& params);

// SACSegmentation with RANSAC, one plane at a time: the largest plane's inliers are taken out
// and the search repeats on the rest until the best plane has fewer than min_inliers.
struct SacParams {
  double distance_threshold = 0.02;  // metres
  int max_iterations = 1000;
  double probability = 0.99;
  unsigned min_inliers = 300;
  int max_planes = 50;
  unsigned seed = 1;
};
PclResult SegmentSac(const OrganizedFrame& frame, const SacParams& params);

}  // namespace relplane::compare
