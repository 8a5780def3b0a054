// The segmenter on a simulated Kinect v1 (the simulator's kinect_v1 model: axial noise growing
// with the square of the depth, depth on the 1/8 pixel disparity lattice): the office at
// 0.5-6 m, every 10th frame, with and without the segmenter told its sensor.

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "scenario_accuracy.hpp"

namespace relplane::segmenter::testing {
namespace {

std::string Scenario(const char* name) {
  return std::string(RELPLANE_SOURCE_DIR) + "/scenarios/" + name + ".yaml";
}

void Print(const char* what, const ScenarioAccuracy& a) {
  std::printf("| %s | %d | %d | %.3f | %.3f | %.3f | %.2f | %.2f | %.1f |\n", what, a.frames,
              a.true_planes, a.Precision(), a.Recall(), a.median_angle_deg,
              a.median_offset_m * 1000, a.min_rms_to_camera, a.max_incidence_deg);
}

// Without a sensor model each plane learns its own noise: the points of one quantized depth
// value (a layer of a tilted wall's staircase, or the last value before the range cut) fit a
// plane with an RMS of zero and are reported as planes. Told its camera (`sensor: kinect_v1`),
// the segmenter never reports a plane flatter than half what the camera resolves along its
// normal at its range, nor one its rays meet beyond the incidence it returns depth from (a
// narrow strip of a wall 4.5 m away, spread along its rays by 3 cm of depth noise, fitted as a
// "wall" containing those rays: on office_kinect_v1 such strips pulled the mapper's pose 0.9 m
// sideways), and finds more of the true planes.
TEST(CameraAccuracy, KinectV1OfficeWithItsSensorModel) {
  const std::string file = Scenario("office_kinect_v1");
  const ScenarioAccuracy blind = MeasureCameraScenario(file, Options{}, 10);
  Print("kinect_v1, no sensor model", blind);
  Options told;
  ASSERT_TRUE(told.sensor.SetPreset("kinect_v1"));
  const ScenarioAccuracy a = MeasureCameraScenario(file, told, 10);
  Print("kinect_v1, sensor: kinect_v1", a);
  ASSERT_GT(a.true_planes, 400);
  EXPECT_LT(blind.min_rms_to_camera, 0.1) << "the layers no longer show without the model";
  EXPECT_GE(a.min_rms_to_camera, told.sensor.layer_rms_share);
  EXPECT_GT(blind.max_incidence_deg, 85.0) << "no strip along the rays without the model";
  EXPECT_LE(a.max_incidence_deg,
            told.sensor.model.max_incidence_deg + told.sensor.grazing_margin_deg);
  EXPECT_GT(a.Precision(), blind.Precision() + 0.05);
  EXPECT_GT(a.Recall(), blind.Recall() + 0.03);
  // The target is 0.95 for both; today's level (docs/results/cameras.md), as a guard.
  EXPECT_GE(a.Precision(), 0.9);
  EXPECT_GE(a.Recall(), 0.86);
  EXPECT_LE(a.median_angle_deg, 1.0);
}

}  // namespace
}  // namespace relplane::segmenter::testing
