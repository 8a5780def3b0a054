// The segmenter on three real, consecutive Kinect frames (../shared/data/kinect): boxes on a
// floor in front of a wall corner. The checks follow what is physically there: one floor, the
// vertical faces of boxes and walls, the top of the low box, and the same large planes in every
// frame.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "relplane/pcd/pcd_reader.hpp"
#include "relplane/segmenter/segmenter.hpp"

namespace relplane::segmenter {
namespace {

const char* const kFrames[] = {
    RELPLANE_SHARED_DIR "/data/kinect/frame_20121214T142255.814212.pcd",
    RELPLANE_SHARED_DIR "/data/kinect/frame_20121214T142256.068683.pcd",
    RELPLANE_SHARED_DIR "/data/kinect/frame_20121214T142256.332395.pcd",
};
constexpr int kLarge = 5000;  // "large": about 2% of a 640x480 frame

// Options for a Kinect-type camera (services/segmenter/kinect.yaml): a few millimetres of
// noise close up, growing with the square of the range.
Options KinectOptions() {
  Options o;
  o.noise.sigma_max = 0.007f;
  o.noise.range_noise = 0.003f;
  return o;
}

Cloud LoadSensorFrame(const std::string& path) {
  pcd::PcdCloud pcd = pcd::ReadPcd(path);
  pcd::OpticalToSensor(&pcd);
  Cloud c;
  c.x = std::move(pcd.x);
  c.y = std::move(pcd.y);
  c.z = std::move(pcd.z);
  return c;
}

double AngleDeg(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return std::acos(std::clamp(a.dot(b), -1.0f, 1.0f)) * 180.0 / M_PI;
}

class KinectFrames : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    Segmenter segmenter(KinectOptions());  // one stream: each frame seeds the next
    for (const char* path : kFrames) {
      const Cloud cloud = LoadSensorFrame(path);
      results_.push_back(segmenter.Segment(cloud));
    }
  }
  static std::vector<Result> results_;
};
std::vector<Result> KinectFrames::results_;

TEST_F(KinectFrames, FindTheFloorBoxFacesAndWallsAsSeparatePlanes) {
  for (size_t f = 0; f < results_.size(); ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    const Result& r = results_[f];
    ASSERT_FALSE(r.planes.empty());
    EXPECT_GT(r.dropped_nonfinite, 0);  // the frames have invalid (NaN) pixels
    const int64_t valid = r.input_points - r.dropped_nonfinite;
    // The floor: most of the view, below the camera (normal towards the camera points up).
    const DetectedPlane& floor = r.planes[0];
    EXPECT_GT(floor.num_points, 0.4 * valid);
    EXPECT_GT(floor.normal.z(), 0.5f);
    EXPECT_GT(floor.d, 0.3f);
    EXPECT_LT(floor.rms, 0.01f);
    std::vector<const DetectedPlane*> large, walls, lids;
    for (const auto& p : r.planes) {
      if (p.num_points < kLarge || &p == &floor) continue;
      const double to_floor = AngleDeg(p.normal, floor.normal);
      if (to_floor < 5.0 && floor.d - p.d > 0.03f) lids.push_back(&p);
      if (to_floor > 5.0) large.push_back(&p);
      if (std::fabs(to_floor - 90.0) < 10.0) walls.push_back(&p);
    }
    // The box's big front face, the wall facing the camera and the side wall of the corner,
    // each a separate plane.
    ASSERT_GE(large.size(), 3u);
    for (size_t i = 0; i < large.size(); ++i) {
      for (size_t j = i + 1; j < large.size(); ++j) {
        const bool distinct = AngleDeg(large[i]->normal, large[j]->normal) > 10.0 ||
                              std::fabs(large[i]->d - large[j]->d) > 0.05f;
        EXPECT_TRUE(distinct) << i << " " << j;
      }
    }
    // The wall corner: two planes standing on the floor at right angles to each other ...
    float wall_range = 0.0f;
    for (const auto* a : walls) {
      for (const auto* b : walls) {
        if (std::fabs(AngleDeg(a->normal, b->normal) - 90.0) > 10.0) continue;
        wall_range = std::max(a->centroid.norm(), b->centroid.norm());
      }
    }
    EXPECT_GT(wall_range, 0.0f) << "no wall corner";
    // ... and a box face in front of them, closer to the camera.
    bool box_face = false;
    for (const auto* p : large) box_face |= p->centroid.norm() < wall_range - 0.2f;
    EXPECT_TRUE(box_face);
    // The low box's top: parallel to the floor, above it, not merged into it.
    EXPECT_GE(lids.size(), 1u);
    // Every extent is a polygon on its plane.
    for (const auto& p : r.planes) {
      EXPECT_GE(p.vertices.size(), 3u);
      for (const auto& v : p.vertices) EXPECT_NEAR(p.normal.dot(v) + p.d, 0.0f, 0.01f);
    }
  }
}

TEST_F(KinectFrames, TheSameLargePlanesInAllThreeFrames) {
  for (size_t f = 0; f < results_.size(); ++f) {
    for (size_t g = 0; g < results_.size(); ++g) {
      if (f == g) continue;
      for (const auto& p : results_[f].planes) {
        if (p.num_points < kLarge) continue;
        double best = 180.0;
        for (const auto& q : results_[g].planes) {
          if (std::fabs(p.d - q.d) < 0.03f) best = std::min(best, AngleDeg(p.normal, q.normal));
        }
        EXPECT_LT(best, 2.0) << "plane of frame " << f << " with " << p.num_points
                             << " points, n = " << p.normal.transpose() << ", d = " << p.d
                             << ", missing in frame " << g;
      }
    }
  }
}

TEST(KinectFrame, EachFrameAloneGivesTheSamePlanesAsTheStream) {
  // Without seeds from a previous frame, proposals alone must find the large planes too.
  Segmenter stream(KinectOptions());
  for (const char* path : kFrames) {
    const Cloud cloud = LoadSensorFrame(path);
    const Result seeded = stream.Segment(cloud);
    const Result alone = Segmenter(KinectOptions()).Segment(cloud);
    for (const auto& p : seeded.planes) {
      if (p.num_points < kLarge) continue;
      double best = 180.0;
      for (const auto& q : alone.planes) {
        if (std::fabs(p.d - q.d) < 0.03f) best = std::min(best, AngleDeg(p.normal, q.normal));
      }
      EXPECT_LT(best, 2.0) << path << ": n = " << p.normal.transpose();
    }
  }
}

}  // namespace
}  // namespace relplane::segmenter
