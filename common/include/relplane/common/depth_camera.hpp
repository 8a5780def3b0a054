#pragma once
// What a depth camera measures and how badly: the noise of its depth along the optical axis,
// the step of its depth quantization, its lateral noise and where it returns nothing. One model
// serves the simulator (which draws noise from it) and the segmenter (which never fits a plane
// tighter than the camera resolves at that range). Depth z is the distance along the optical
// axis, metres (relplane's sensor frame: x forward, so z = x).

#include <optional>
#include <string>
#include <vector>

namespace relplane::camera {

// How the camera reports depth: as a disparity in fixed sub-pixel steps (structured light and
// active stereo: the depth step grows with z^2) or as depth in fixed steps (time of flight, and
// the 1 mm unit of 16-bit depth images).
enum class Quantization { kNone, kDisparity, kDepth };

struct DepthCameraModel {
  std::string name = "gaussian";
  // Axial noise sigma_z(z) = axial_a + axial_lin * z + axial_quad * (z - axial_c)^2, metres.
  // Nguyen, Izadi and Lovell (3DIMPVT 2012) measured a Kinect v1 at 0.0012 + 0.0019 (z - 0.4)^2.
  double axial_a = 0.0;
  double axial_lin = 0.0;
  double axial_quad = 0.0;
  double axial_c = 0.0;
  Quantization quantization = Quantization::kNone;
  // Disparity d = focal_px * baseline / z, reported in steps of disparity_step pixels: the depth
  // step is z^2 * disparity_step / (focal_px * baseline) (Khoshelham and Elberink, Sensors
  // 2012: about 2.85e-3 z^2 m for a Kinect v1's 1/8 pixel).
  double focal_px = 580.0;        // pixels
  double baseline = 0.075;        // metres
  double disparity_step = 0.125;  // pixels
  double depth_step = 0.001;      // metres, with Quantization::kDepth
  // Lateral noise: the depth reported at a pixel is the surface's depth at a pixel displaced by
  // this standard deviation in each image direction (Nguyen et al.: about 0.8 px for a Kinect v1
  // away from grazing angles), in pixels of focal_px.
  double lateral_px = 0.0;
  // No return nearer than min_depth or further than max_depth (metres along the axis), nor
  // where the ray meets the surface more than max_incidence_deg from its normal.
  double min_depth = 0.0;
  double max_depth = 1e9;
  double max_incidence_deg = 90.0;

  // Standard deviation of the depth noise before quantization at depth z, metres.
  double AxialSigma(double z) const;
  // Distance between neighbouring depth values the camera can report at depth z (0 without
  // quantization), metres.
  double DepthStep(double z) const;
  // What the camera resolves at depth z: its noise and its quantization's (a uniform step of
  // width s has standard deviation s / sqrt(12)), metres.
  double ResolvedSigma(double z) const;
  // The depth the camera reports for a depth z: z itself, or the nearest value on its
  // disparity or depth lattice. Returns 0 where no lattice value exists (z <= 0).
  double Quantize(double z) const;
};

// Named presets: kinect_v1, realsense_d435, tof. nullopt for an unknown name.
std::optional<DepthCameraModel> Preset(const std::string& name);
// The names Preset knows, for error messages.
std::vector<std::string> PresetNames();

}  // namespace relplane::camera
