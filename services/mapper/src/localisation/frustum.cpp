#include "localisation/frustum.hpp"

#include <algorithm>
#include <cmath>

namespace relplane::mapper {

using Eigen::Vector2d;

void LearnedFrustum::Observe(const Eigen::Vector2d& edge) {
  const double bearing = std::abs(std::atan2(edge.y(), edge.x()));
  max_bearing_ = std::max(max_bearing_, bearing);
  const int bin = std::min(kBins - 1, static_cast<int>(bearing / kBinWidth));
  ++counts_[bin];
  // The pile-up: the fullest bin in the outer part of what has been seen.
  if (bin > mode_bin_ && counts_[bin] >= counts_[mode_bin_]) mode_bin_ = bin;
  if (counts_[bin] > counts_[mode_bin_] && bin * kBinWidth > 0.5 * max_bearing_) mode_bin_ = bin;
  const int rbin = std::min(kRangeBins - 1, static_cast<int>(edge.norm() / kRangeBin));
  ++range_counts_[rbin];
  max_range_bin_ = std::max(max_range_bin_, rbin);
  if (++observed_ % 64 == 0) UpdateRangeLimit();
}

void LearnedFrustum::ObserveSampling(const Observation& obs) {
  // Walls with plenty of points only: a sliver's extent says little of its points' spacing.
  constexpr int kSlices = 16;  // the rectangle's solid angle is summed over slices along it
  if (obs.support < view_.min_support || !(obs.z_max > obs.z_min)) return;
  // The solid angle of the wall's rectangle between its edges and heights: over slices along
  // it, the bearing each spans times the sine of the elevation at its top less at its bottom.
  double omega = 0.0;
  for (int k = 0; k < kSlices; ++k) {
    const Vector2d a = obs.edge[0] + (obs.edge[1] - obs.edge[0]) * (k / double(kSlices));
    const Vector2d b = obs.edge[0] + (obs.edge[1] - obs.edge[0]) * ((k + 1) / double(kSlices));
    const double span =
        std::abs(std::remainder(std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x()), 2.0 * M_PI));
    const double r = 0.5 * (a.norm() + b.norm());
    omega += span * (obs.z_max / std::hypot(obs.z_max, r) - obs.z_min / std::hypot(obs.z_min, r));
  }
  if (!(omega > 0.0)) return;
  const double log_per_ray = std::log(omega / obs.support);
  const int bin = static_cast<int>((log_per_ray - kStepLogMin) / kStepBin);
  if (bin < 0 || bin >= kStepBins) return;
  ++step_counts_[bin];
  ++steps_observed_;
  if (steps_observed_ < view_.min_walls || steps_observed_ % 16 != 0) return;
  // The median: a wall with a door, or partly hidden, spans more than its points cover.
  int below = 0;
  for (int b = 0; b < kStepBins; ++b) {
    below += step_counts_[b];
    if (2 * below >= steps_observed_) {
      step_ = std::sqrt(std::exp(kStepLogMin + (b + 0.5) * kStepBin));
      break;
    }
  }
}

double LearnedFrustum::AngularStep() const { return step_; }

double EdgeSpacing(double step, const Eigen::Vector2d& edge, double d) {
  if (step <= 0.0) return 0.0;
  return step * edge.squaredNorm() / std::max(d, 0.05);
}

double LearnedFrustum::EdgeSpacing(const Eigen::Vector2d& edge, double d) const {
  return mapper::EdgeSpacing(step_, edge, d);
}

void LearnedFrustum::UpdateRangeLimit() {
  // The farthest pile-up that stands out from the distances just below it with next to nothing
  // beyond: edges cut by the range are the farthest the sensor reports. The fullest bin is not
  // it: a sensor turning in place sees one wall end at one distance for many frames, and such an
  // interior pile outgrew the range's (3.92 m against 5.92-5.98 m on a 6 m sensor) and hid it,
  // so that range-cut ends passed for wall ends. Once learnt, a limit is kept until a pile
  // farther out replaces it: the edges past a range pile are range cuts too (seen at other
  // angles, a hallway's walls all cut 0.3 m short of an 8 m range), not wall ends.
  constexpr int kSpread = 3;  // bins either side of the pile's peak that still belong to it
  constexpr int kBelow = 25;  // bins (0.5 m) below it to compare with
  int beyond = 0;             // edges past the candidate pile
  for (int peak = max_range_bin_; peak >= 0; --peak) {
    if (peak + kSpread + 1 <= max_range_bin_) beyond += range_counts_[peak + kSpread + 1];
    // No pile further in has next to nothing beyond it.
    if (view_.pile_beyond_ratio * beyond > observed_) return;
    if (range_counts_[peak] < view_.min_pile) continue;
    int pile = 0, below = 0;
    for (int b = std::max(0, peak - kSpread); b <= std::min(kRangeBins - 1, peak + kSpread); ++b) {
      pile += range_counts_[b];
    }
    for (int b = std::max(0, peak - kSpread - kBelow); b < peak - kSpread; ++b) {
      below += range_counts_[b];
    }
    const double below_per_bin = static_cast<double>(below) / kBelow;
    if (range_counts_[peak] > view_.pile_contrast * below_per_bin &&
        beyond <= pile / view_.pile_beyond_ratio) {
      // The farthest full bin may be the pile's upper flank (edge noise): its fullest bin is
      // where the range cuts.
      int mode = peak;
      for (int b = std::max(0, peak - kSpread); b < peak; ++b) {
        if (range_counts_[b] > range_counts_[mode]) mode = b;
      }
      range_limit_ = (mode + kSpread + 1) * kRangeBin;
      return;
    }
  }
}

double LearnedFrustum::Limit() const {
  if (counts_[mode_bin_] < view_.min_pile) return max_bearing_;
  return std::min(max_bearing_, (mode_bin_ + 1) * kBinWidth);
}

double LearnedFrustum::RangeLimit() const { return range_limit_; }

bool LearnedFrustum::Clipped(const Eigen::Vector2d& edge) const {
  // The edge's bearing is uncertain by its position noise over its range.
  const double range = edge.norm();
  const double margin = view_.bearing_margin + std::atan2(edge_noise_, range);
  if (std::abs(std::atan2(edge.y(), edge.x())) > Limit() - margin) return true;
  return range > RangeLimit() - edge_noise_ - 4 * kRangeBin;
}

bool LearnedFrustum::Clipped(const Eigen::Vector2d& edge, const Eigen::Vector2d& other) const {
  if (Clipped(edge)) return true;
  // Rays meeting a wall at a glancing angle sample it sparsely along its length: the last sample
  // within the range lies short of it by up to a sample's spacing, which grows as the rays graze
  // the wall (a side wall 2.25 m off a 6 m sensor's path was first seen range-cut 5.93 m away,
  // short of where the distance alone says cut, and put a group 1.56 m off). The edge is cut if
  // the wall past it reaches that distance within the bearing margin, as seen from the sensor:
  // the next sample along it may have been out of range (§II.C: no static edge).
  const double range = RangeLimit() - edge_noise_ - 4 * kRangeBin;  // as above
  const double length = (edge - other).norm();
  if (!std::isfinite(range) || length <= 0.0) return false;
  const Eigen::Vector2d t = (edge - other) / length;  // along the wall, past this edge
  const double along = t.dot(edge);  // from the foot of the perpendicular from the sensor
  if (along <= 0.0) return false;    // the wall comes nearer past this edge
  const double normal = std::abs(t.x() * edge.y() - t.y() * edge.x());
  if (normal >= range) return false;
  const double gap = std::acos(normal / range) - std::atan2(along, normal);
  return gap < view_.bearing_margin + std::atan2(edge_noise_, edge.norm());
}

}  // namespace relplane::mapper
