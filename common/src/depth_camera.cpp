#include "relplane/common/depth_camera.hpp"

#include <cmath>

namespace relplane::camera {

double DepthCameraModel::AxialSigma(double z) const {
  return axial_a + axial_lin * z + axial_quad * (z - axial_c) * (z - axial_c);
}

double DepthCameraModel::DepthStep(double z) const {
  switch (quantization) {
    case Quantization::kDisparity:
      return z * z * disparity_step / (focal_px * baseline);
    case Quantization::kDepth:
      return depth_step;
    case Quantization::kNone:
      break;
  }
  return 0.0;
}

double DepthCameraModel::ResolvedSigma(double z) const {
  const double sigma = AxialSigma(z);
  const double step = DepthStep(z);
  return std::sqrt(sigma * sigma + step * step / 12.0);
}

double DepthCameraModel::Quantize(double z) const {
  if (!(z > 0.0)) return 0.0;
  switch (quantization) {
    case Quantization::kDisparity: {
      const double fb = focal_px * baseline;
      const double steps = std::round(fb / z / disparity_step);
      return steps > 0.0 ? fb / (steps * disparity_step) : 0.0;
    }
    case Quantization::kDepth: {
      const double steps = std::round(z / depth_step);
      return steps > 0.0 ? steps * depth_step : 0.0;
    }
    case Quantization::kNone:
      break;
  }
  return z;
}

std::optional<DepthCameraModel> Preset(const std::string& name) {
  DepthCameraModel m;
  m.name = name;
  if (name == "kinect_v1") {
    // Structured light: Nguyen et al.'s axial noise, disparity in 1/8 pixel steps with the
    // IR camera's 580 px focal length and the 7.5 cm projector baseline (Khoshelham and
    // Elberink 2012), 0.8 px lateral noise; it returns depth from about 0.5 m, and little
    // that is usable beyond 6 m or at grazing incidence.
    m.axial_a = 0.0012;
    m.axial_quad = 0.0019;
    m.axial_c = 0.4;
    m.quantization = Quantization::kDisparity;
    m.focal_px = 580.0;
    m.baseline = 0.075;
    m.disparity_step = 0.125;
    m.lateral_px = 0.8;
    m.min_depth = 0.5;
    m.max_depth = 6.0;
    m.max_incidence_deg = 80.0;
    return m;
  }
  if (name == "realsense_d435") {
    // Active stereo: Intel's depth RMS error z^2 * subpixel / (focal * baseline) with 0.08 px
    // subpixel, 50 mm baseline and 424 px focal length at 848 x 480; depth in 1 mm units.
    m.axial_quad = 0.08 / (424.0 * 0.050);
    m.quantization = Quantization::kDepth;
    m.focal_px = 424.0;
    m.baseline = 0.050;
    m.depth_step = 0.001;
    m.lateral_px = 0.5;
    m.min_depth = 0.3;
    m.max_depth = 6.0;
    m.max_incidence_deg = 80.0;
    return m;
  }
  if (name == "tof") {
    // Time of flight (Kinect v2, Azure Kinect class): a few millimetres of noise growing
    // slowly with range (Fankhauser et al. 2015 measured 1.5-4 mm over 1-4 m on a Kinect v2),
    // depth reported in millimetres, multipath left out.
    m.axial_a = 0.0015;
    m.axial_lin = 0.0006;
    m.quantization = Quantization::kDepth;
    m.focal_px = 365.0;
    m.depth_step = 0.001;
    m.lateral_px = 0.3;
    m.min_depth = 0.5;
    m.max_depth = 5.5;
    m.max_incidence_deg = 80.0;
    return m;
  }
  return std::nullopt;
}

std::vector<std::string> PresetNames() { return {"kinect_v1", "realsense_d435", "tof"}; }

}  // namespace relplane::camera
