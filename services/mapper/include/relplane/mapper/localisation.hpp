#pragma once
// §II.D current position from the present untransformed observations against the global map,
// and §II.E the motion model when only one partial plane is in view.

#include <algorithm>
#include <cmath>
#include <vector>

#include "relplane/common/geometry.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/state.hpp"

namespace relplane::mapper {

enum class PoseStatus { kTracking, kMotionModel, kInitializing, kLost };

struct PoseEstimate {
  geometry::Pose2 pose;
  PoseStatus status = PoseStatus::kLost;
  int planes = 0;  // planes used
};

// One observation of a mapped wall: what is seen now and where the map has it.
struct Sighting {
  const Observation* obs = nullptr;
  const RltPlane* plane = nullptr;
  Placement world;
};

// The sensor's horizontal field of view as learned from the edges it reports. Edges cut by the
// view pile up at one bearing (every wall crossing the border gives one, every frame), while
// wall ends spread over all bearings: the field of view is the most frequent bearing among the
// widest ones. The widest bearing alone would do without noise, but one noisy edge close by
// widens it for good and the cut edges then pass for wall ends. An edge near the border is cut
// by the view, not a wall's end. (Range is not learned: in a small world no wall reaches it and
// a far wall end would pass for the limit.)
class LearnedFrustum {
 public:
  void Observe(const Eigen::Vector2d& edge) {
    const double bearing = std::abs(std::atan2(edge.y(), edge.x()));
    max_bearing_ = std::max(max_bearing_, bearing);
    const int bin = std::min(kBins - 1, static_cast<int>(bearing / kBinWidth));
    ++counts_[bin];
    // The pile-up: the fullest bin in the outer part of what has been seen.
    if (bin > mode_bin_ && counts_[bin] >= counts_[mode_bin_]) mode_bin_ = bin;
    if (counts_[bin] > counts_[mode_bin_] && bin * kBinWidth > 0.5 * max_bearing_) mode_bin_ = bin;
  }
  // The half field of view: the pile-up's upper bin edge once it stands out, else the widest.
  double Limit() const {
    if (counts_[mode_bin_] < kMinPile) return max_bearing_;
    return std::min(max_bearing_, (mode_bin_ + 1) * kBinWidth);
  }
  bool Clipped(const Eigen::Vector2d& edge) const {
    // The edge's bearing is uncertain by its position noise over its range.
    const double margin = kBearingMargin + std::atan2(kEdgeNoise, edge.norm());
    return std::abs(std::atan2(edge.y(), edge.x())) > Limit() - margin;
  }

 private:
  static constexpr double kBearingMargin = 0.035;  // rad (2 degrees)
  static constexpr double kEdgeNoise = 0.03;       // m, a wall end's position noise (2 sigma)
  static constexpr double kBinWidth = 0.0087;      // rad (0.5 degrees)
  static constexpr int kBins = 362;                // up to pi
  static constexpr int kMinPile = 20;
  double max_bearing_ = 0.0;
  int counts_[kBins] = {};
  int mode_bin_ = 0;
};

// Solves the sensor pose: yaw from the mean orientation difference, position by least squares
// over the walls' lines (one equation each) and their static edges seen now (one more each, along
// the wall), with `previous` as a weak prior. With a single wall, or walls that leave the position
// underdetermined, the result is the motion model (§II.E): the wall stays where the map has it,
// the unobserved direction keeps its previous value, and a mapped wall end seen at its predicted
// place pins the position along the wall.
PoseEstimate Localise(const std::vector<Sighting>& sightings, const geometry::Pose2& previous,
                      const LearnedFrustum& frustum, const LocalisationOptions& options);

}  // namespace relplane::mapper
