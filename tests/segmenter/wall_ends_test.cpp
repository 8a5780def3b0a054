// Wall ends from a wall's furthest samples (wall_ends.hpp), by hand and through the segmenter.

#include "relplane/segmenter/wall_ends.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "relplane/segmenter/segmenter.hpp"
#include "synthetic_scene.hpp"

namespace relplane::segmenter {
namespace {

// Columns of `rows` samples each, `spacing` apart along the wall, the last at `last`, each
// sample moved outwards by Gaussian noise of `sigma`; rows 1 cm apart up the wall.
EndBuffer Columns(float last, float spacing, int columns, int rows, float sigma, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, sigma);
  EndBuffer buffer;
  for (int c = 0; c < columns; ++c) {
    for (int r = 0; r < rows; ++r) {
      buffer.Add(last - c * spacing + (sigma > 0.0f ? noise(rng) : 0.0f), 0.01f * r);
    }
  }
  return buffer;
}

TEST(EndBuffer, KeepsTheSamplesFurthestOut) {
  EndBuffer buffer;
  std::vector<float> outs;
  for (int i = 0; i < 200; ++i) outs.push_back(static_cast<float>((i * 37) % 200));
  for (float out : outs) buffer.Add(out, 0.0f);
  ASSERT_EQ(buffer.Size(), EndBuffer::kCapacity);
  float least = std::numeric_limits<float>::infinity();
  for (const auto& s : buffer) least = std::min(least, s.out);
  EXPECT_EQ(least, 200.0f - EndBuffer::kCapacity);
}

TEST(EstimateEnd, WithoutASpacingItIsTheExtremeAndWithoutSamplesNothing) {
  EXPECT_EQ(EstimateEnd(EndBuffer{}, EndSampling{0.05f, 0.01f, 1.0f}),
            -std::numeric_limits<float>::infinity());
  const EndBuffer buffer = Columns(2.0f, 0.05f, 3, 30, 0.0f, 1);
  EXPECT_FLOAT_EQ(EstimateEnd(buffer, EndSampling{}), 2.0f);
}

TEST(EstimateEnd, SparseColumnsPutTheEndHalfASpacingPastTheLast) {
  // Far off at a grazing angle: columns 10 cm apart, the wall's end anywhere up to the next.
  const EndBuffer buffer = Columns(3.0f, 0.1f, 3, 40, 0.0f, 1);
  EXPECT_NEAR(EstimateEnd(buffer, EndSampling{0.1f, 0.01f, 1.0f}), 3.05f, 1e-5f);
}

TEST(EstimateEnd, NoiseAlongTheWallDoesNotPushTheEndOut) {
  // 40 rows with 1 cm noise: the furthest sample lies about 2.2 sigma out, the estimate at the
  // column plus half a spacing, whatever the draw.
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    const EndBuffer buffer = Columns(3.0f, 0.1f, 3, 40, 0.01f, seed);
    float extreme = -std::numeric_limits<float>::infinity();
    for (const auto& s : buffer) extreme = std::max(extreme, s.out);
    EXPECT_GT(extreme, 3.015f);
    EXPECT_NEAR(EstimateEnd(buffer, EndSampling{0.1f, 0.01f, 1.0f}), 3.05f, 0.005f);
  }
}

TEST(EstimateEnd, DenseColumnsPutTheEndAtTheEdgeOfTheSamples) {
  // Nearby: columns 5 mm apart under 1 cm noise; the samples run out at 3.0025 (the last
  // column plus half a spacing) smeared by the noise. Where columns are denser than the noise
  // the smear leaves a little more than half a column beyond the edge's mean place: the
  // estimate lands up to 0.4 sigma out (wall_ends.hpp), against 2-3 sigma for the extreme.
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    const EndBuffer buffer = Columns(3.0f, 0.005f, 40, 40, 0.01f, seed);
    float extreme = -std::numeric_limits<float>::infinity();
    for (const auto& s : buffer) extreme = std::max(extreme, s.out);
    EXPECT_GT(extreme, 3.0025f + 0.01f);  // the extreme: over a sigma past the edge
    EXPECT_NEAR(EstimateEnd(buffer, EndSampling{0.005f, 0.01f, 1.0f}), 3.0025f, 0.01f);
  }
}

TEST(EstimateEnd, ASubsampleTakesFewerOfEachColumn) {
  // One in four of the sensor's samples: a column holds a quarter of its rows.
  std::mt19937 rng(5);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  EndBuffer buffer;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 160; r += 4) buffer.Add(3.0f - 0.1f * c + noise(rng), 0.0025f * r);
  }
  EXPECT_NEAR(EstimateEnd(buffer, EndSampling{0.1f, 0.0025f, 0.25f}), 3.05f, 0.006f);
}

// A hallway wall ending at the side of a pilaster, seen from 2.5 to 4.5 m before its end by a
// level noise-free 160 x 120, 90 degree sensor: the mean error of the wall's far end, and the
// mixture planes that formed no piece over the run.
struct FarEnd {
  double mean_error = 0.0;
  int seen = 0;
  int pieceless = 0;
};

FarEnd MeasureFarEnd() {
  using testing::Rect;
  const double h = 2.5, wall_y = 1.0, end = 11.0;
  const std::vector<Rect> world = {
      {{-1, -1.25, 0}, {14, 0, 0}, {0, 2.25, 0}},              // floor
      {{-1, -1.25, h}, {0, 2.25, 0}, {14, 0, 0}},              // ceiling
      {{-1, wall_y, 0}, {end + 1, 0, 0}, {0, 0, h}},           // the wall, to the left
      {{end, wall_y - 0.3, 0}, {0, 0.3, 0}, {0, 0, h}},        // the pilaster's near side
      {{end, wall_y - 0.3, 0}, {0.4, 0, 0}, {0, 0, h}},        // its front
      {{end + 0.4, wall_y - 0.3, 0}, {0, 0.3, 0}, {0, 0, h}},  // its far side
      {{end + 0.4, wall_y, 0}, {2, 0, 0}, {0, 0, h}},          // the wall after it
      {{-1, -1.25, 0}, {0, 0, h}, {14, 0, 0}},                 // the wall to the right
  };
  Segmenter segmenter;
  FarEnd out;
  double sum = 0.0;
  for (double x = end - 4.5; x <= end - 2.5 + 1e-9; x += 0.05) {
    testing::Sensor sensor;
    sensor.width = 160;
    sensor.height = 120;
    sensor.hfov_deg = 90.0;
    sensor.max_range = 8.0;
    sensor.world_from_sensor = Eigen::Isometry3d(Eigen::Translation3d(x, 0, 1.0));
    const Result r = segmenter.Segment(testing::Render(world, sensor).cloud);
    out.pieceless += r.pieceless_planes;
    for (const DetectedPlane& p : r.planes) {
      if (std::fabs(p.normal.y() + 1.0f) > 0.05f || std::fabs(p.d - wall_y) > 0.05) continue;
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const auto& v : p.vertices) {
        lo = std::min(lo, x + v.x());
        hi = std::max(hi, x + v.x());
      }
      if (lo > end || hi < end - 0.7) continue;  // the wall after the pilaster
      sum += hi - end;
      ++out.seen;
    }
  }
  if (out.seen > 0) out.mean_error = sum / out.seen;
  return out;
}

// The samples land 9-26 cm apart along the wall there: the extreme point alone falls short by
// about half that spacing.
TEST(WallEndEstimate, AFarEndIsNotShortByHalfARaySpacing) {
  const FarEnd estimated = MeasureFarEnd();
  ASSERT_GT(estimated.seen, 30);
  std::printf("far end, mean error: %+.4f m\n", estimated.mean_error);
  // Within half the closest spacing (the extreme points alone: about 9 cm short). Still a
  // little short: the step learnt from the cloud is the densest quarter's, and a 90 degree
  // pinhole's rays are 30 % closer there than near the middle of the view.
  EXPECT_LT(std::fabs(estimated.mean_error), 0.045);
}

// On these noise-free frames a row of floor samples, one of ceiling samples and the wall's
// column at one depth form a mixture plane with no piece: it is dropped and counted.
TEST(WallEndEstimate, PlanesWithoutAPieceAreDropped) {
  const FarEnd far_end = MeasureFarEnd();
  EXPECT_GT(far_end.pieceless, 0);
  EXPECT_GT(far_end.seen, 30);
}

}  // namespace
}  // namespace relplane::segmenter
