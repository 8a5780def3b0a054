#pragma once
// Where a wall's ends lie, from its points furthest out along it. The sensor samples a wall on a
// grid of rays, so the last sample short of an end lands anywhere up to one ray spacing inside
// it, and the noise along the rays spreads each column of samples along the wall: the extreme
// point is short of the end by half a spacing on average far away (grazing samples 5-10 cm
// apart) and, over the column's many rows, past it by about 2.4 sigma nearby. Either way the
// error has one sign wherever the wall is seen from, so a §II.C static edge averaged over its
// sightings keeps it and a leg of the route comes out short.

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

// The end's coordinate outwards: where the points run out, less the noise's spread and plus
// half a column spacing. The k-th point from the outside with k half of one column's points
// (the column's height over its row spacing) sits at the last column whatever the noise, and
// where columns are denser than the noise it sits half a spacing inside the edge of the
// points' spread; half a column spacing then puts it where the next column would be cut off on
// average; where columns are denser than the noise the smear leaves the estimate up to 0.4
// sigma out. The plain extreme when the spacing is unknown (0), -infinity with no points.
float EstimateEnd(const EndBuffer& buffer, const EndSampling& sampling);

}  // namespace relplane::segmenter
