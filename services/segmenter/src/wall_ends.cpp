#include "relplane/segmenter/wall_ends.hpp"

#include <algorithm>

namespace relplane::segmenter {
namespace {

bool Further(const EndBuffer::Sample& x, const EndBuffer::Sample& y) { return x.out > y.out; }

}  // namespace

void EndBuffer::Add(float out, float up) {
  if (size_ < kCapacity) {
    samples_[size_++] = Sample{out, up};
    std::push_heap(samples_.begin(), samples_.begin() + size_, Further);
    return;
  }
  if (out <= samples_[0].out) return;  // the heap's top is the least far of the kept ones
  std::pop_heap(samples_.begin(), samples_.begin() + size_, Further);
  samples_[size_ - 1] = Sample{out, up};
  std::push_heap(samples_.begin(), samples_.begin() + size_, Further);
}

float EstimateEnd(const EndBuffer& buffer, const EndSampling& sampling) {
  if (buffer.Size() == 0) return -std::numeric_limits<float>::infinity();
  std::array<EndBuffer::Sample, EndBuffer::kCapacity> sorted{};
  const int n = buffer.Size();
  std::copy(buffer.begin(), buffer.end(), sorted.begin());
  std::sort(sorted.begin(), sorted.begin() + n, Further);
  if (!(sampling.column_spacing > 0.0f) || !(sampling.row_spacing > 0.0f)) return sorted[0].out;
  // The last column's height: the kept points are its own and its neighbours' (of the same
  // height), the noise along the wall drawing them from all its rows.
  float lo = sorted[0].up, hi = sorted[0].up;
  for (int i = 1; i < n; ++i) {
    lo = std::min(lo, sorted[i].up);
    hi = std::max(hi, sorted[i].up);
  }
  const float column_points = sampling.share * ((hi - lo) / sampling.row_spacing + 1.0f);
  const int k = std::clamp(static_cast<int>(std::lround(0.5f * column_points)), 1, n);
  return sorted[k - 1].out + 0.5f * sampling.column_spacing;
}

}  // namespace relplane::segmenter
