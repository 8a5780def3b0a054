#pragma once
// Where a wall's ends lie, from its points furthest out along it. The sensor samples a wall on a
// grid of rays, so the last sample short of an end lands anywhere up to one ray spacing inside
// it, and the noise along the rays spreads each column of samples along the wall: the extreme
// point is short of the end by half a spacing on average far off (grazing samples 5-40 cm
// apart) and, over the column's many rows, past it by 2-3 sigma nearby. The sign of the error
// goes with the distance the end is seen from, so a §II.C static edge fitted from far off and
// localised against from nearby sets the pose back along the route.

#include <array>
#include <cmath>
#include <limits>

namespace relplane::segmenter {

// The points of a wall furthest out at one end: each one's coordinate outwards along the wall
// (`out`) and up it (`up`). Holds the kCapacity largest `out` seen (a min-heap on it), with no
// allocation.
class EndBuffer {
 public:
  static constexpr int kCapacity = 48;
  struct Sample {
    float out = 0.0f;
    float up = 0.0f;
  };

  void Add(float out, float up);
  int Size() const { return size_; }
  const Sample* begin() const { return samples_.data(); }
  const Sample* end() const { return samples_.data() + size_; }

 private:
  std::array<Sample, kCapacity> samples_{};
  int size_ = 0;
};

// How the sensor saw the end: the spacing of its columns of samples along the wall and of its
// rows up the wall there, and which share of the sensor's rays the buffer's points are (a
// subsampled cloud keeps every column but fewer of each one's points).
struct EndSampling {
  float column_spacing = 0.0f;  // metres along the wall
  float row_spacing = 0.0f;     // metres up the wall
  float share = 1.0f;           // of the sensor's samples, in (0, 1]
};

// The end's coordinate outwards: the k-th point from the outside, k half of one column's points
// (the column's height over its row spacing, times the share), plus half a column spacing.
// Where the columns lie further apart than the noise spreads them, the k-th point sits at the
// last column whatever the noise, and half a spacing puts the end where the next column would
// have been cut off on average. Where they are denser, it sits about half a spacing inside the
// edge of the points' spread, and the estimate lands within 0.4 sigma of the edge. The plain
// extreme when a spacing is unknown (0); -infinity with no points.
float EstimateEnd(const EndBuffer& buffer, const EndSampling& sampling);

}  // namespace relplane::segmenter
