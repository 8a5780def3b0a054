#include "relplane/accuracy/plane_errors.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace relplane::accuracy {
namespace {

using Eigen::Vector3d;

// A jamb-like face on x = 3, from y = -2 to y = -1.6, 2.7 m high.
sim::TruePlane Jamb() {
  sim::TruePlane wall;
  wall.id = 7;
  wall.normal = Vector3d(1, 0, 0);
  wall.d = -3.0;
  wall.corners = {Vector3d(3, -2, 0), Vector3d(3, -1.6, 0), Vector3d(3, -1.6, 2.7),
                  Vector3d(3, -2, 2.7)};
  wall.centroid = Vector3d(3, -1.8, 1.35);
  return wall;
}

// A sensor at (0, 0, 1.2) looking along +x turned by 30 degrees (the jamb's foot is then not on
// the sensor's axis), and a detection given in the world frame, returned in the sensor's.
Eigen::Isometry3d Sensor() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Vector3d(0, 0, 1.2);
  t.linear() = Eigen::AngleAxisd(-M_PI / 6, Vector3d::UnitZ()).toRotationMatrix();
  return t;
}

segmenter::DetectedPlane Seen(const Vector3d& normal, const Vector3d& centroid) {
  const Eigen::Isometry3d to_sensor = Sensor().inverse();
  segmenter::DetectedPlane p;
  p.normal = (to_sensor.linear() * normal).cast<float>();
  p.centroid = (to_sensor * centroid).cast<float>();
  p.d = -p.normal.dot(p.centroid);
  p.num_points = 500;
  return p;
}

// A fit through the face's centroid turned by 0.01 rad: no error at the centroid, 1.8 m times
// the turn at the foot of the perpendicular from the sensor (y = 0), on the sensor's side.
TEST(PlaneErrors, AFitTurnedAboutItsCentroidIsOffAtTheFootByTheLeverTimesTheTurn) {
  const double turn = 0.01;
  const Vector3d normal(-std::cos(turn), -std::sin(turn), 0.0);  // towards the sensor
  const auto errors = PlaneErrors(4, Sensor(), {Seen(normal, Vector3d(3, -1.8, 1.2))}, {Jamb()});
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].seq, 4);
  EXPECT_EQ(errors[0].true_id, 7);
  EXPECT_NEAR(errors[0].true_length_m, 0.4, 1e-9);
  EXPECT_NEAR(errors[0].range_m, std::hypot(3.0, 1.8), 1e-5);
  EXPECT_EQ(errors[0].points, 500);
  EXPECT_NEAR(errors[0].centroid_error_m, 0.0, 1e-5);
  EXPECT_NEAR(errors[0].foot_error_m, 1.8 * std::tan(turn), 1e-5);
  EXPECT_NEAR(errors[0].normal_error_deg, turn * 180.0 / M_PI, 1e-4);
}

// The detection's own RMS, and its extent along the wall seen from above.
TEST(PlaneErrors, TheFitsOwnRmsAndHorizontalLengthGoAlong) {
  const Vector3d normal(-1.0, 0.0, 0.0);
  segmenter::DetectedPlane seen = Seen(normal, Vector3d(3, -1.8, 1.2));
  seen.rms = 0.004f;
  const Eigen::Isometry3d to_sensor = Sensor().inverse();
  for (const Vector3d& corner : {Vector3d(3, -2.0, 0.5), Vector3d(3, -1.65, 0.5),
                                 Vector3d(3, -1.65, 2.0), Vector3d(3, -2.0, 2.0)}) {
    seen.vertices.push_back((to_sensor * corner).cast<float>());
  }
  const auto errors = PlaneErrors(4, Sensor(), {seen}, {Jamb()});
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NEAR(errors[0].rms_m, 0.004, 1e-7);
  EXPECT_NEAR(errors[0].length_m, 0.35, 1e-5);
}

// A fit 1 cm nearer the sensor than the face is 1 cm off, positive, at both places; its normal
// pointing away from the sensor changes nothing.
TEST(PlaneErrors, AFitNearerTheSensorIsPositiveWhicheverWayItsNormalPoints) {
  for (const double sign : {-1.0, 1.0}) {
    const auto errors =
        PlaneErrors(0, Sensor(), {Seen(Vector3d(sign, 0, 0), Vector3d(2.99, -1.7, 1.5))}, {Jamb()});
    ASSERT_EQ(errors.size(), 1u) << sign;
    EXPECT_NEAR(errors[0].centroid_error_m, 0.01, 1e-5) << sign;
    EXPECT_NEAR(errors[0].foot_error_m, 0.01, 1e-5) << sign;
  }
}

// Only a vertical fit that faces the wall, lies near its plane and within its ends is scored.
TEST(PlaneErrors, DetectionsOnNoTrueWallAreLeftOut) {
  const std::vector<segmenter::DetectedPlane> detections = {
      Seen(Vector3d(0, 0, 1), Vector3d(3, -1.8, 0.0)),     // the floor
      Seen(Vector3d(-1, 0, 0), Vector3d(2.7, -1.8, 1.2)),  // 0.3 m off its plane
      Seen(Vector3d(-1, 0, 0), Vector3d(3, -1.2, 1.2)),    // 0.4 m past its end
      Seen(Vector3d(-std::cos(0.2), -std::sin(0.2), 0), Vector3d(3, -1.8, 1.2)),  // 11.5 deg
  };
  EXPECT_TRUE(PlaneErrors(0, Sensor(), detections, {Jamb()}).empty());
}

TEST(PlaneErrors, TheCsvHasAHeaderAndARowPerError) {
  PlaneError e;
  e.seq = 12;
  e.true_id = 3;
  e.true_length_m = 0.4;
  e.range_m = 2.5;
  e.points = 321;
  e.centroid_error_m = 0.0001;
  e.foot_error_m = -0.0123;
  e.normal_error_deg = 1.25;
  e.rms_m = 0.0042;
  e.length_m = 0.375;
  EXPECT_EQ(PlaneErrorsCsv({e}),
            "seq,true_id,true_length_m,range_m,points,centroid_error_m,foot_error_m,"
            "normal_error_deg,rms_m,length_m\n"
            "12,3,0.400,2.500,321,0.00010,-0.01230,1.2500,0.00420,0.375\n");
}

}  // namespace
}  // namespace relplane::accuracy
