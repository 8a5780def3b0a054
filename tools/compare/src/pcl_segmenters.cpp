// The only source that includes PCL (its headers are slow to compile). Frames arrive in
// relplane's sensor frame (x forward, y left, z up) and are handed to PCL in the camera's
// optical frame (x right, y down, z forward): PCL's integral-image normals and its
// depth-dependent thresholds take z as the depth. Planes come back in the sensor frame.

#include "relplane/compare/pcl_segmenters.hpp"

#include <pcl/ModelCoefficients.h>
#include <pcl/features/integral_image_normal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/segmentation/organized_multi_plane_segmentation.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <chrono>
#include <cmath>

namespace relplane::compare {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

pcl::PointXYZ Optical(const segmenter::Cloud& c, size_t i) { return {-c.y[i], -c.z[i], c.x[i]}; }

// A plane n . p + d = 0 found in the optical frame, in the sensor frame (a rotation: d stays).
PlaneFit FromOptical(const pcl::ModelCoefficients& m, std::vector<int> indices) {
  PlaneFit fit;
  fit.nx = m.values[2];
  fit.ny = -m.values[0];
  fit.nz = -m.values[1];
  fit.d = m.values[3];
  fit.indices = std::move(indices);
  return fit;
}

}  // namespace

PclResult SegmentOrganized(const OrganizedFrame& frame, const OrganizedParams& params) {
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>(
      static_cast<uint32_t>(frame.width), static_cast<uint32_t>(frame.height));
  for (size_t i = 0; i < frame.points.size(); ++i) (*cloud)[i] = Optical(frame.points, i);
  cloud->is_dense = false;

  const Clock::time_point start = Clock::now();
  auto normals = pcl::make_shared<pcl::PointCloud<pcl::Normal>>();
  pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
  // The covariance method fits a plane to each pixel's window, the smoother of the two PCL offers
  // for real-time use (the other, AVERAGE_3D_GRADIENT, is cheaper and noisier); PCL's organized
  // segmentation demo pairs it with OrganizedMultiPlaneSegmentation.
  ne.setNormalEstimationMethod(params.covariance_normals ? ne.COVARIANCE_MATRIX
                                                         : ne.AVERAGE_3D_GRADIENT);
  ne.setMaxDepthChangeFactor(params.max_depth_change);
  ne.setNormalSmoothingSize(static_cast<float>(params.normal_smoothing));
  ne.setInputCloud(cloud);
  ne.compute(*normals);

  pcl::OrganizedMultiPlaneSegmentation<pcl::PointXYZ, pcl::Normal, pcl::Label> mps;
  mps.setMinInliers(params.min_inliers);
  // PCL scales the distance threshold between neighbours' plane offsets with depth squared, as
  // a Kinect's noise grows (Trevor et al. 2013): 2 cm at 1 m is 32 cm at 4 m.
  mps.setAngularThreshold(params.angular_threshold_deg * M_PI / 180.0);
  mps.setDistanceThreshold(params.distance_threshold);
  mps.setMaximumCurvature(params.max_curvature);
  mps.setInputCloud(cloud);
  mps.setInputNormals(normals);
  std::vector<pcl::PlanarRegion<pcl::PointXYZ>,
              Eigen::aligned_allocator<pcl::PlanarRegion<pcl::PointXYZ>>>
      regions;
  std::vector<pcl::ModelCoefficients> models;
  std::vector<pcl::PointIndices> inliers, label_indices, boundaries;
  auto labels = pcl::make_shared<pcl::PointCloud<pcl::Label>>();
  // With the refinement step that grows each plane into the unlabelled pixels beside it that lie
  // on its model, as PCL's organized segmentation demo runs it.
  mps.segmentAndRefine(regions, models, inliers, labels, label_indices, boundaries);
  PclResult result;
  result.seconds = Seconds(start);

  // The refinement appends grown pixels to a plane's inliers and may append one twice: each
  // pixel goes to the last plane that took it.
  std::vector<int> owner(frame.points.size(), -1);
  for (size_t m = 0; m < inliers.size(); ++m) {
    for (int i : inliers[m].indices) owner[static_cast<size_t>(i)] = static_cast<int>(m);
  }
  std::vector<std::vector<int>> members(inliers.size());
  for (size_t i = 0; i < owner.size(); ++i) {
    if (owner[i] >= 0) members[static_cast<size_t>(owner[i])].push_back(static_cast<int>(i));
  }
  for (size_t m = 0; m < models.size(); ++m) {
    result.planes.push_back(FromOptical(models[m], std::move(members[m])));
  }
  return result;
}

PclResult SegmentSac(const OrganizedFrame& frame, const SacParams& params) {
  // RANSAC needs finite points: the finite pixels, and where each came from.
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  std::vector<int> pixel;
  for (size_t i = 0; i < frame.points.size(); ++i) {
    const pcl::PointXYZ p = Optical(frame.points, i);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    cloud->push_back(p);
    pixel.push_back(static_cast<int>(i));
  }

  const Clock::time_point start = Clock::now();
  // random = false: PCL seeds its samplers with the fixed 12345 instead of the time, so a run
  // repeats exactly (SACSegmentation builds a fresh model, so a fresh seed, on every call).
  pcl::SACSegmentation<pcl::PointXYZ> seg(/*random=*/false);
  seg.setModelType(pcl::SACMODEL_PLANE);
  seg.setMethodType(pcl::SAC_RANSAC);
  // A least-squares refit on the inliers, PCL's default: what a user gets.
  seg.setOptimizeCoefficients(true);
  seg.setDistanceThreshold(params.distance_threshold);
  seg.setMaxIterations(params.max_iterations);
  seg.setProbability(params.probability);
  seg.setInputCloud(cloud);
  auto remaining = pcl::make_shared<pcl::Indices>(cloud->size());
  for (size_t i = 0; i < remaining->size(); ++i) (*remaining)[i] = static_cast<int>(i);
  PclResult result;
  std::vector<uint8_t> taken(cloud->size(), 0);
  while (remaining->size() >= params.min_inliers &&
         static_cast<int>(result.planes.size()) < params.max_planes) {
    seg.setIndices(remaining);
    pcl::PointIndices found;
    pcl::ModelCoefficients model;
    seg.segment(found, model);
    if (found.indices.size() < params.min_inliers) break;
    std::vector<int> pixels;
    pixels.reserve(found.indices.size());
    for (int i : found.indices) {
      taken[static_cast<size_t>(i)] = 1;
      pixels.push_back(pixel[static_cast<size_t>(i)]);
    }
    result.planes.push_back(FromOptical(model, std::move(pixels)));
    auto rest = pcl::make_shared<pcl::Indices>();
    rest->reserve(remaining->size() - found.indices.size());
    for (int i : *remaining) {
      if (!taken[static_cast<size_t>(i)]) rest->push_back(i);
    }
    remaining = rest;
  }
  result.seconds = Seconds(start);
  return result;
}

}  // namespace relplane::compare
