#include "relplane/accuracy/legs.hpp"

#include <cmath>

#include "relplane/common/geometry.hpp"

namespace relplane::accuracy {
namespace {

constexpr double kSameHeadingRad = 1e-3;

Leg Measure(const FramePose& a, const FramePose& b) {
  const double cx = std::cos(a.true_yaw), cy = std::sin(a.true_yaw);
  const double ex = (b.x - b.true_x) - (a.x - a.true_x);
  const double ey = (b.y - b.true_y) - (a.y - a.true_y);
  Leg leg;
  leg.first_seq = a.seq;
  leg.last_seq = b.seq;
  leg.length_m = std::hypot(b.true_x - a.true_x, b.true_y - a.true_y);
  leg.along_error_m = ex * cx + ey * cy;
  return leg;
}

}  // namespace

std::vector<Leg> StraightLegs(const std::vector<FramePose>& poses, double min_length_m) {
  std::vector<Leg> legs;
  const FramePose* first = nullptr;
  const FramePose* last = nullptr;
  const auto close = [&] {
    if (first == nullptr) return;
    const Leg leg = Measure(*first, *last);
    if (leg.length_m >= min_length_m) legs.push_back(leg);
  };
  for (const FramePose& p : poses) {
    if (p.status < 0) continue;  // refused: no pose to measure
    if (first != nullptr &&
        std::abs(geometry::WrapAngle(p.true_yaw - first->true_yaw)) > kSameHeadingRad) {
      close();
      first = nullptr;
    }
    if (first == nullptr) first = &p;
    last = &p;
  }
  close();
  return legs;
}

double AlongTrackPercent(const std::vector<Leg>& legs) {
  double along = 0.0, length = 0.0;
  for (const Leg& leg : legs) {
    along += leg.along_error_m;
    length += leg.length_m;
  }
  return length > 0.0 ? 100.0 * along / length : 0.0;
}

}  // namespace relplane::accuracy
