#pragma once
// The depth camera the segmenter is told about (a preset by name): its noise along each ray at
// the point's depth replaces what the segmenter would otherwise learn from the data alone.
// With it, no plane is fitted tighter than the camera resolves at its range, the band a point
// supports a plane in grows with its depth (as CAPE and PEAC grow theirs), planes at range
// merge within what the camera resolves there, and a plane flatter than the camera can measure
// (the points of one quantized depth value) is no surface, nor is one the camera's rays meet
// at an incidence it returns nothing from.

#include <Eigen/Core>
#include <string>

#include "relplane/common/depth_camera.hpp"

namespace relplane::segmenter {

struct SensorOptions {
  // kinect_v1, realsense_d435, tof (relplane/common/depth_camera.hpp), or empty: no camera
  // model (noise learnt per plane, Options::range_noise).
  std::string preset;
  camera::DepthCameraModel model;  // filled from the preset by SetPreset
  // A reported plane whose RMS is below this share of the noise the camera resolves along its
  // normal at its range is the set of points of one quantized depth (a flat layer of a tilted
  // surface's staircase), not a surface: it is dropped and its points assigned again.
  float layer_rms_share = 0.5f;
  // With the camera's noise known, what a plane learns on top of it is the surface's own
  // roughness: at most this (metres; caps Options::sigma_max). A wider band lets a large plane
  // take in the small faces beside it.
  float surface_sigma_max = 0.005f;
  // degrees: a reported plane the rays meet more than the camera's max_incidence_deg plus this
  // from its normal (at its centroid) is no surface the camera returns depth from, but samples
  // of another surface spread along their rays by the depth noise: it is dropped and its points
  // assigned again. The margin covers the fitted normal's own error.
  float grazing_margin_deg = 2.0f;

  bool Known() const { return !preset.empty(); }
  // Sets preset and model; false for an unknown name (nothing changed).
  bool SetPreset(const std::string& name);
  // Variance the camera adds along the ray of a point (x forward: x is the depth), metres^2.
  float VarianceAt(float depth) const;
  // What the camera resolves along a plane's normal for points near `point` (sensor frame):
  // the depth noise moves a point along its ray by the change in depth over the ray's depth.
  float SigmaAlongNormal(const Eigen::Vector3f& normal, const Eigen::Vector3f& point) const;
  // Whether a plane through `centroid` (sensor frame) with `normal` faces the ray to its
  // centroid beyond the camera's incidence limit and the margin. A real surface cannot: the
  // centroid's distance is at most its farthest point's, so the cosine of its incidence,
  // |normal . centroid| / |centroid|, is at least its least one among the points returned.
  bool BeyondIncidence(const Eigen::Vector3f& normal, const Eigen::Vector3f& centroid) const;
  // How far apart two near-parallel planes (normals and centroids) may lie and be one surface:
  // `base`, or with a camera at least three times what it resolves along them at their
  // centroids (a surface at range is seen spread as far as the camera's depth steps).
  float CoplanarDistance(float base, const Eigen::Vector3f& normal_a,
                         const Eigen::Vector3f& centroid_a, const Eigen::Vector3f& normal_b,
                         const Eigen::Vector3f& centroid_b) const;
};

// The noise variance a sensor adds along the ray of the point (x, y, z): the camera's at its
// depth when one is known, else (range_noise * r^2)^2 (0 without range noise).
inline float PointNoiseVariance(const SensorOptions& sensor, float range_noise, float x, float y,
                                float z) {
  if (sensor.Known()) return sensor.VarianceAt(x);
  const float r2 = x * x + y * y + z * z;
  return range_noise * range_noise * r2 * r2;
}

inline bool HasPointNoise(const SensorOptions& sensor, float range_noise) {
  return sensor.Known() || range_noise > 0.0f;
}

}  // namespace relplane::segmenter
