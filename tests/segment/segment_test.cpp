// relplane-segment's library: frames read by file type, one frame segmented, the table, the
// JSON and the SVG it writes.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "relplane/segment/depth_frame.hpp"
#include "relplane/segment/plane_report.hpp"
#include "relplane/segment/planes_svg.hpp"
#include "relplane/segment/segment_frame.hpp"

namespace relplane::segment {
namespace {

// A temporary file with `text`, removed with the object.
class TempFile {
 public:
  TempFile(const std::string& suffix, const std::string& text) {
    char name[] = "/tmp/relplane-segment-test-XXXXXX";
    const int fd = mkstemp(name);
    close(fd);
    std::remove(name);
    path_ = std::string(name) + suffix;
    std::ofstream(path_) << text;
  }
  ~TempFile() { std::remove(path_.c_str()); }
  const std::string& Path() const { return path_; }

 private:
  std::string path_;
};

const char* const kTwoByTwoPcd =
    "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 2\n"
    "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n1 2 3\n4 5 6\nnan nan nan\n7 8 9\n";

TEST(ReadDepthFrameTest, ReadsAPcdByItsTypeAsAnOrganizedFrame) {
  const TempFile file(".pcd", kTwoByTwoPcd);
  const DepthFrame frame = ReadDepthFrame(file.Path(), {});
  EXPECT_EQ(frame.name, file.Path().substr(file.Path().find_last_of('/') + 1));
  EXPECT_EQ(frame.width, 2);
  EXPECT_EQ(frame.height, 2);
  EXPECT_TRUE(frame.Organized());
  ASSERT_EQ(frame.x.size(), 4u);
  EXPECT_EQ(frame.x[1], 4.0f);
  EXPECT_EQ(frame.z[3], 9.0f);
  EXPECT_TRUE(std::isnan(frame.y[2]));
}

TEST(ReadDepthFrameTest, OpticalFramesAreTurnedIntoTheSensorFrame) {
  const TempFile file(".PCD", kTwoByTwoPcd);
  const DepthFrame frame = ReadDepthFrame(file.Path(), {true});
  // Optical (x right, y down, z forward) -> sensor (x forward, y left, z up).
  EXPECT_EQ(frame.x[0], 3.0f);
  EXPECT_EQ(frame.y[0], -1.0f);
  EXPECT_EQ(frame.z[0], -2.0f);
}

TEST(ReadDepthFrameTest, UnknownTypesAndBadFilesAreOneLineErrorsNamingTheFile) {
  try {
    ReadDepthFrame("/tmp/frame.xyz", {});
    FAIL() << "an unknown file type";
  } catch (const FrameError& e) {
    EXPECT_EQ(std::string(e.what()), "/tmp/frame.xyz: unknown file type (known: .pcd)");
  }
  try {
    ReadDepthFrame("/no/such/frame.pcd", {});
    FAIL() << "a missing file";
  } catch (const FrameError& e) {
    EXPECT_NE(std::string(e.what()).find("/no/such/frame.pcd"), std::string::npos) << e.what();
  }
}

segmenter::DetectedPlane Wall() {
  segmenter::DetectedPlane p;
  p.normal = Eigen::Vector3f(-1, 0, 0);
  p.d = 3.0f;
  p.vertices = {{3, 1, -1}, {3, -1, -1}, {3, -1, 0.5f}, {3, 1, 0.5f}};
  p.num_points = 1234;
  p.rms = 0.0021f;
  return p;
}

TEST(ExtentSizeTest, AlongTheHorizontalLineOfThePlaneAndAcrossIt) {
  const Eigen::Vector2f wall = ExtentSize(Wall());
  EXPECT_NEAR(wall.x(), 2.0f, 1e-5f);
  EXPECT_NEAR(wall.y(), 1.5f, 1e-5f);
  segmenter::DetectedPlane floor;
  floor.normal = Eigen::Vector3f(0, 0, 1);
  floor.vertices = {{1, -0.5f, -1}, {4, -0.5f, -1}, {4, 0.5f, -1}, {1, 0.5f, -1}};
  const Eigen::Vector2f size = ExtentSize(floor);
  EXPECT_NEAR(size.x(), 3.0f, 1e-5f);  // along the sensor's x
  EXPECT_NEAR(size.y(), 1.0f, 1e-5f);
  EXPECT_EQ(ExtentSize(segmenter::DetectedPlane{}), Eigen::Vector2f::Zero());
}

TEST(PlaneTableTest, OneRowPerPlane) {
  FramePlanes frame{"f.pcd", 307200, 1000, {Wall()}};
  EXPECT_EQ(PlaneTable(frame),
            "f.pcd: 1 planes, 307200 points (1000 invalid)\n"
            "   #   normal x   normal y   normal z     d (m)    points  rms (mm)  extent (m)\n"
            "   0    -1.0000     0.0000     0.0000    3.0000      1234       2.1  2.00 x 1.50\n");
  EXPECT_EQ(PlaneTable({"e.pcd", 10, 10, {}}), "e.pcd: 0 planes, 10 points (10 invalid)\n");
}

TEST(PlanesJsonTest, EveryFrameAndPlaneWithUnits) {
  const std::string json = PlanesJson({{"f.pcd", 307200, 1000, {Wall()}}});
  for (const char* field :
       {"\"schema\": \"relplane-segment/1\"", "\"file\": \"f.pcd\"", "\"points\": 307200",
        "\"invalid_points\": 1000", "\"normal\": [-1, 0, 0]", "\"d\": 3", "\"points\": 1234",
        "\"extent_size\": [2, 1.5]", "\"vertices\": [", "[3, 1, -1]"}) {
    EXPECT_NE(json.find(field), std::string::npos) << field << " in\n" << json;
  }
}

// A 160x120 pinhole view of a wall 3 m ahead above a floor 1 m below the sensor.
DepthFrame WallAndFloor() {
  DepthFrame frame;
  frame.name = "synthetic";
  frame.width = 160;
  frame.height = 120;
  for (int v = 0; v < frame.height; ++v) {
    for (int u = 0; u < frame.width; ++u) {
      const Eigen::Vector3f ray(1.0f, (80 - u) / 100.0f, (60 - v) / 100.0f);
      const float to_wall = 3.0f;
      const float to_floor = ray.z() < 0 ? 1.0f / -ray.z() : 1e9f;
      const Eigen::Vector3f p = ray * std::min(to_wall, to_floor);
      frame.x.push_back(p.x());
      frame.y.push_back(p.y());
      frame.z.push_back(p.z());
    }
  }
  return frame;
}

TEST(SegmentFrameTest, FindsTheWallAndTheFloorAndLabelsEveryPoint) {
  segmenter::Options options;
  options.keep_labels = true;
  segmenter::Segmenter seg(options);
  const DepthFrame frame = WallAndFloor();
  std::vector<int32_t> labels;
  const FramePlanes planes = SegmentFrame(seg, frame, &labels);
  EXPECT_EQ(planes.name, "synthetic");
  EXPECT_EQ(planes.points, 160 * 120);
  EXPECT_EQ(labels.size(), frame.x.size());
  bool wall = false, floor = false;
  for (const segmenter::DetectedPlane& p : planes.planes) {
    wall |= p.normal.x() < -0.999f && std::fabs(p.d - 3.0f) < 0.01f;
    floor |= p.normal.z() > 0.999f && std::fabs(p.d - 1.0f) < 0.01f;
  }
  EXPECT_TRUE(wall) << PlaneTable(planes);
  EXPECT_TRUE(floor) << PlaneTable(planes);

  const std::string svg = PlanesSvg({{frame, labels, planes.planes}}, 100.0);
  EXPECT_EQ(svg.rfind("<svg xmlns='http://www.w3.org/2000/svg'", 0), 0u);
  EXPECT_NE(svg.find("synthetic: " + std::to_string(planes.planes.size()) + " planes"),
            std::string::npos);
  EXPECT_NE(svg.find("<polygon points="), std::string::npos);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
}

}  // namespace
}  // namespace relplane::segment
