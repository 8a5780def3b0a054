#pragma once
// The sensor's view (field of view, range limit, angular step) as the mapper learns it from the
// edges and walls the sensor reports: an edge at the view's border is cut by it, not a wall's
// end (§II.C).

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "plane_store/observation.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// The sensor's view as learned from the edges it reports. Edges cut by the view pile up at one
// bearing (every wall crossing the border gives one, every frame), while wall ends spread over
// all bearings: the field of view is the most frequent bearing among the widest ones. The
// widest bearing alone would do without noise, but one noisy edge close by widens it for good
// and the cut edges then pass for wall ends. The range limit is learned the same way, from the
// farthest pile-up of edge distances with next to nothing beyond it (not the fullest: a wall end
// seen while turning in place piles up too): in a small world no wall reaches the range and
// nothing piles up there, so no limit is learned. An edge near either limit is cut by the view,
// not a wall's end (a sensor turning in place sees a range-cut edge stand still, like a wall
// end).
class LearnedFrustum {
 public:
  // `options.localisation.edge_noise` widens the margins an edge is judged cut within.
  explicit LearnedFrustum(const MapperOptions& options = {})
      : view_(options.view), edge_noise_(options.localisation.edge_noise) {}

  void Observe(const Eigen::Vector2d& edge);
  // The half field of view: the pile-up's upper bin edge once it stands out, else the widest.
  double Limit() const;
  // The range limit, or infinity while none stands out.
  double RangeLimit() const;
  bool Clipped(const Eigen::Vector2d& edge) const;
  // The same for a wall's edge, `other` its other edge: also cut where the wall runs on past it
  // and reaches the range within the bearing margin (rays grazing a wall sample it sparsely,
  // and the last sample in range may lie well short of the limit).
  bool Clipped(const Eigen::Vector2d& edge, const Eigen::Vector2d& other) const;
  // The sensor's angular sampling step, learnt from the walls seen: a wall's solid angle over
  // the points that support it is the solid angle per ray. Nought until enough are seen.
  void ObserveSampling(const Observation& obs);
  double AngularStep() const;
  double EdgeNoise() const { return edge_noise_; }
  // How far apart the sensor's samples land along a wall at its edge `edge` (sensor frame), the
  // wall's line `d` from the sensor: the step times r^2 / d. Nought while the step is unknown.
  double EdgeSpacing(const Eigen::Vector2d& edge, double d) const;

 private:
  static constexpr double kBinWidth = 0.0087;  // rad (0.5 degrees)
  static constexpr int kBins = 362;            // up to pi
  static constexpr double kRangeBin = 0.02;    // m
  static constexpr int kRangeBins = 2500;      // up to 50 m
  void UpdateRangeLimit();
  ViewOptions view_;
  double edge_noise_;  // m (LocalisationOptions::edge_noise)
  double max_bearing_ = 0.0;
  int counts_[kBins] = {};
  int mode_bin_ = 0;
  std::vector<int> range_counts_ = std::vector<int>(kRangeBins, 0);
  int max_range_bin_ = 0;
  int observed_ = 0;
  double range_limit_ = std::numeric_limits<double>::infinity();
  // Per observation, log of its solid angle per supporting point over bins of kStepBin.
  static constexpr double kStepBin = 0.02;
  static constexpr int kStepBins = 600;  // exp(-18) to exp(-6) sr: steps of 0.12 mrad to 50 mrad
  static constexpr double kStepLogMin = -18.0;
  std::vector<int> step_counts_ = std::vector<int>(kStepBins, 0);
  int steps_observed_ = 0;
  double step_ = 0.0;
};

// How far apart a sensor with `step` rad between its rays lands its samples along a wall at its
// edge `edge` (from the sensor), the wall's line `d` from the sensor: step r^2 / d. Nought while
// the step is not known (not positive).
double EdgeSpacing(double step, const Eigen::Vector2d& edge, double d);

}  // namespace relplane::mapper
