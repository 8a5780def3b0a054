#include "relplane/segmenter/hull.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace relplane::segmenter {
namespace {

// A float's bits as an unsigned integer in the float's order (negative floats have the sign
// bit and count down): points then sort as one 64-bit key each, several times faster than by
// a comparison of two floats. -0 is first made +0, as the floats compare equal.
uint32_t OrderedBits(float f) {
  f += 0.0f;
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  return (bits & 0x80000000u) ? ~bits : bits | 0x80000000u;
}

float FromOrderedBits(uint32_t key) {
  const uint32_t bits = (key & 0x80000000u) ? key & 0x7fffffffu : ~key;
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// Sorts the points by x, then y, and drops repeated points.
void SortUnique(std::vector<Eigen::Vector2f>* points) {
  std::vector<uint64_t> keys(points->size());
  for (size_t i = 0; i < keys.size(); ++i) {
    const Eigen::Vector2f& p = (*points)[i];
    keys[i] = static_cast<uint64_t>(OrderedBits(p.x())) << 32 | OrderedBits(p.y());
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  points->resize(keys.size());
  for (size_t i = 0; i < keys.size(); ++i) {
    (*points)[i] = Eigen::Vector2f(FromOrderedBits(static_cast<uint32_t>(keys[i] >> 32)),
                                   FromOrderedBits(static_cast<uint32_t>(keys[i])));
  }
}

float Cross(const Eigen::Vector2f& o, const Eigen::Vector2f& a, const Eigen::Vector2f& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

}  // namespace

std::vector<Eigen::Vector2f> ConvexHull(std::vector<Eigen::Vector2f> points) {
  SortUnique(&points);
  if (points.size() < 3) return points;
  std::vector<Eigen::Vector2f> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {  // lower chain
    while (k >= 2 && Cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && Cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

}  // namespace relplane::segmenter
