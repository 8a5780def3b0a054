#pragma once
// The rltplane (Fig. 1): one wall's untransformed observations by iteration, plus what the
// pairwise comparisons learn about it (growth phases, static edges, full length).

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <deque>
#include <utility>
#include <vector>

#include "plane_store/observation.hpp"
#include "relplane/common/geometry.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// What every comparison an observation is in needs of it alone (§II.C), worked out once when it
// is stored: with 30 walls in view each observation is in some 30 comparisons.
struct ObservationTerms {
  double alpha = 0.0;                                        // Observation::Alpha()
  Eigen::Matrix2d rotation_t = Eigen::Matrix2d::Identity();  // R(alpha)^T
  double weight = 0.0;                                       // OrientationWeight
  double blur = 0.0;  // its fit's bias over its length (comparison.cpp)
};

class RltPlane {
 public:
  // `phase_hysteresis` and `max_observations` as in ComparisonOptions and MapperOptions.
  RltPlane(int64_t id, Observation first, double phase_hysteresis, int max_observations,
           const RltPlaneOptions& options = {}, const FitOptions& fit = {});

  int64_t Id() const { return id_; }
  // Appends an observation (iterations strictly increasing) and tracks growth (§II.C).
  void Add(Observation obs);

  const std::deque<Observation>& Observations() const { return observations_; }
  const Observation& Latest() const { return observations_.back(); }
  // The terms of Observations()[i].
  const ObservationTerms& Terms(size_t i) const { return terms_[i]; }
  int64_t FirstSeen() const { return first_seen_; }
  int64_t LastSeen() const { return observations_.back().iteration; }
  int64_t Count() const { return count_; }
  // Index of the first stored observation with iteration >= `iteration`.
  size_t LowerBound(int64_t iteration) const;
  // The observation at `iteration`, or nullptr.
  const Observation* At(int64_t iteration) const;
  // Marks edge `e` of the stored observation at `index` as cut by the view: the view is learnt
  // as it is used, and an edge judged before the range limit was known is judged again.
  void MarkCut(size_t index, int e) {
    observations_.at(index).cut[e] = true;
    observations_.at(index).coarse[e] = false;
  }
  // Marks edge `e` of the stored observation at `index` as one the sensor's samples do not
  // resolve (Observation::coarse), judged again once the sensor's angular step is learnt.
  void MarkCoarse(size_t index, int e) {
    observations_.at(index).cut[e] = true;
    observations_.at(index).coarse[e] = true;
  }

  // §II.C: "the interval must be split up if a plane changes state from growing to shrinking".
  // The phase of an iteration: phases change where the visible length turns from growing to
  // shrinking (or back), placed retroactively at the turning point.
  // Returns the first iteration of that phase (stable over the run).
  int64_t PhaseAt(int64_t iteration) const;
  int64_t LatestPhaseStart() const { return phase_starts_.back(); }

  // Largest visible length seen in two of three sightings in a row (§II.C "maximum size of a
  // plane"); once the wall has been seen whole (both edges static at once) the median length
  // over those sightings.
  double Length() const;
  bool FullLengthKnown() const { return !full_ranges_.empty(); }
  // Drops the observations before `iteration` (the latest one is always kept): what
  // regrouping can no longer reach (§II.F storage). What was learned from them stays.
  void DropBefore(int64_t iteration);
  // Marks iterations [first, last] as ones where both edges were static: the wall seen whole.
  void MarkFull(int64_t first, int64_t last);
  double ZMin() const { return z_min_; }
  double ZMax() const { return z_max_; }

  // Which edges the comparisons found static in the current interval (set each iteration).
  bool static_now[2] = {false, false};
  int64_t static_now_iteration = -1;

  // The pose estimated at its latest observation: its extent on the map once the pose history
  // has forgotten that iteration (a wall known only by its line).
  geometry::Pose2 latest_pose;
  bool latest_pose_known = false;

  // Its first observation, from the pose then: the first group is anchored on it (§II.D) long
  // after the observation itself has been dropped.
  SeenWall first_seen;

  // Groups this plane belongs to, in creation order (§II.B).
  std::vector<int64_t> groups;

  // The largest OrientationWeight of the stored observations (0 when there is none).
  double BestOrientationWeight() const {
    return weight_max_.empty() ? 0.0 : std::max(0.0, weight_max_.front().second);
  }

 private:
  // Whether `iteration` lies in a range where the wall was seen whole.
  bool InFullRange(int64_t iteration) const;
  // Keeps a dropped whole sighting's length in the thinned sample.
  void Retire(double length);

  int64_t id_;
  double hysteresis_;
  RltPlaneOptions options_;
  FitOptions fit_;
  size_t max_observations_;
  std::deque<Observation> observations_;
  std::deque<ObservationTerms> terms_;  // one per observation
  int64_t first_seen_;
  int64_t count_ = 0;
  double max_length_ = 0.0;
  std::vector<std::pair<int64_t, int64_t>> full_ranges_;
  mutable double full_length_ = 0.0;  // computed lazily from full_ranges_
  mutable bool full_dirty_ = false;
  mutable bool full_valid_ = false;  // full_length_ was computed from stored sightings
  // When full_length_ was last computed: the newest range alone gave it its sightings (the
  // first options_.full_length_sightings of them from `capped_from_`, the first one counted),
  // starting at `capped_first_`. A range that only grows at its end, as the one seen whole now does
  // at every iteration, then leaves it as it is.
  mutable bool capped_ = false;
  mutable int64_t capped_first_ = 0;
  mutable int64_t capped_from_ = 0;
  // Lengths of whole sightings already dropped (bounded memory): a sample of at most
  // options_.retired_lengths, every retired_stride_-th one of the retired_count_ so far (Retire),
  // so the full length still counts them.
  std::vector<float> retired_lengths_;
  int64_t retired_stride_ = 1;
  int64_t retired_count_ = 0;
  double z_min_;
  double z_max_;
  // Growth tracking: phase starts (iteration, first of the phase), current trend and extreme.
  std::vector<int64_t> phase_starts_;
  bool growing_ = true;
  std::vector<double> recent_lengths_;  // the last few visible lengths
  double length_noise_ = 0.0;           // estimated standard deviation of the visible length
  double extreme_length_ = 0.0;
  int64_t extreme_iteration_ = 0;
  // The stored observations whose OrientationWeight no later one reaches, oldest first, as
  // (iteration, weight): the front is the largest weight of those stored (a sliding-window
  // maximum, kept as observations are added and dropped). Every group placement asks for it,
  // and going through all stored observations each time took a tenth of an iteration.
  std::deque<std::pair<int64_t, double>> weight_max_;
};

// The same weight for a mapped wall from the best fit among its kept observations: how far its
// orientation can be trusted when a group is turned onto the map (a door jamb or a sliver of
// wall seen over a few centimetres must not turn walls metres long).
double OrientationWeight(const RltPlane& plane);

}  // namespace relplane::mapper
