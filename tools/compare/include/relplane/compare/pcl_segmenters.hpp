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
  // Normals are not smoothed across a depth jump of more than this factor of the depth, over a
  // window of this many pixels: the values of PCL's tutorial on integral-image normals.
  float max_depth_change = 0.02f;
  double normal_smoothing = 10.0;
  unsigned min_inliers = 300;  // the truth's "in view" (PCL's default: 1000)
  // PCL's defaults: neighbouring normals within 3 degrees, plane offsets within 2 cm scaled by
  // depth squared, a region's curvature (smallest eigenvalue over the trace) under 0.001.
  double angular_threshold_deg = 3.0;
  double distance_threshold = 0.02;  // metres at 1 m
  double max_curvature = 0.001;
};
PclResult SegmentOrganized(const OrganizedFrame& frame, const OrganizedParams& params);

// SACSegmentation with RANSAC, one plane at a time: the largest plane's inliers are taken out
// and the search repeats on the rest until the best plane has fewer than min_inliers.
struct SacParams {
  double distance_threshold = 0.02;  // metres; relplane-compare sets it per frame (SacThreshold)
  // PCL's default of 50 iterations finds a plane with 99 % confidence only when it holds more
  // than about 45 % of the points left; 1,000 finds one of 17 %.
  int max_iterations = 1000;
  double probability = 0.99;
  unsigned min_inliers = 300;  // the truth's "in view"
  int max_planes = 50;         // a bound on the time of a frame of clutter
};
PclResult SegmentSac(const OrganizedFrame& frame, const SacParams& params);

}  // namespace relplane::compare
