#include "plane_store/rltplane.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "comparison/comparison.hpp"

namespace relplane::mapper {
namespace {

double Median3(double a, double b, double c) {
  return std::max(std::min(a, b), std::min(std::max(a, b), c));
}

}  // namespace

RltPlane::RltPlane(int64_t id, Observation first, double phase_hysteresis, int max_observations,
                   const RltPlaneOptions& options, const FitOptions& fit)
    : id_(id),
      hysteresis_(phase_hysteresis),
      options_(options),
      fit_(fit),
      max_observations_(static_cast<size_t>(std::max(max_observations, 16))),
      first_seen_(first.iteration),
      z_min_(first.z_min),
      z_max_(first.z_max) {
  phase_starts_.push_back(first.iteration);
  extreme_length_ = first.Length();
  extreme_iteration_ = first.iteration;
  Add(std::move(first));
}

void RltPlane::Add(Observation obs) {
  if (!observations_.empty() && obs.iteration <= observations_.back().iteration) return;
  const double raw_length = obs.Length();
  const int64_t it = obs.iteration;
  // The visible length's noise, from its second differences (zero for steady growth): the
  // mean absolute second difference of white noise is 1.95 sigma.
  recent_lengths_.push_back(raw_length);
  if (recent_lengths_.size() > static_cast<size_t>(options_.smoothing)) {
    recent_lengths_.erase(recent_lengths_.begin());
  }
  const size_t n = recent_lengths_.size();
  if (n >= 3) {
    const double second =
        std::abs(recent_lengths_[n - 1] - 2.0 * recent_lengths_[n - 2] + recent_lengths_[n - 3]);
    length_noise_ +=
        (second / 1.95 - length_noise_) / std::min<double>(count_, options_.noise_window);
  }
  // §II.C growth tracking with hysteresis on the mean of the last few lengths, the hysteresis
  // at least a few times the length noise, so noise alone never turns a steady plane from
  // growing to shrinking (each turn splits the comparison intervals). The new phase starts
  // just after the extreme so the split is where the trend really turned, not where it was
  // noticed.
  double length = 0.0;
  for (double l : recent_lengths_) length += l;
  length /= static_cast<double>(n);
  const double hysteresis = std::max(hysteresis_, options_.noise_hysteresis * length_noise_);
  if (growing_) {
    if (length >= extreme_length_) {
      extreme_length_ = length;
      extreme_iteration_ = it;
    } else if (length < extreme_length_ - hysteresis) {
      phase_starts_.push_back(extreme_iteration_ + 1);
      growing_ = false;
      extreme_length_ = length;
      extreme_iteration_ = it;
    }
  } else {
    if (length <= extreme_length_) {
      extreme_length_ = length;
      extreme_iteration_ = it;
    } else if (length > extreme_length_ + hysteresis) {
      phase_starts_.push_back(extreme_iteration_ + 1);
      growing_ = true;
      extreme_length_ = length;
      extreme_iteration_ = it;
    }
  }
  // §II.C's maximum size, from lengths seen in two of three sightings in a row: a wall's
  // visible length changes smoothly as the sensor moves, and one sighting longer than both its
  // neighbours is a segmentation outlier (a door jamb seen once several times its length, a
  // strip of floor along its foot taken with it, moves the wall placed beside it across the
  // hallway). The first two sightings stand until a third can confirm them.
  const double confirmed =
      n >= 3 ? Median3(recent_lengths_[n - 3], recent_lengths_[n - 2], recent_lengths_[n - 1])
             : raw_length;
  max_length_ = n == 3 ? confirmed : std::max(max_length_, confirmed);
  z_min_ = std::min(z_min_, obs.z_min);
  z_max_ = std::max(z_max_, obs.z_max);
  terms_.push_back(ComparisonTerms(obs, fit_));
  const double weight = terms_.back().weight;
  if (!std::isnan(weight)) {  // a NaN is never the largest (std::max keeps the other)
    while (!weight_max_.empty() && weight_max_.back().second <= weight) weight_max_.pop_back();
    weight_max_.emplace_back(it, weight);
  }
  observations_.push_back(std::move(obs));
  ++count_;
  if (observations_.size() > max_observations_) {
    DropBefore(observations_[observations_.size() - max_observations_].iteration);
  }
}

void RltPlane::DropBefore(int64_t iteration) {
  if (observations_.empty() || observations_.front().iteration >= iteration) return;
  while (observations_.size() > 1 && observations_.front().iteration < iteration) {
    if (InFullRange(observations_.front().iteration)) Retire(observations_.front().Length());
    observations_.pop_front();
    terms_.pop_front();
  }
  const int64_t first = observations_.front().iteration;
  while (!weight_max_.empty() && weight_max_.front().first < first) weight_max_.pop_front();
  // Phase starts older than the stored observations are no longer needed.
  while (phase_starts_.size() > 2 && phase_starts_[1] <= first) {
    phase_starts_.erase(phase_starts_.begin());
  }
  // Whole-sighting ranges before the stored observations are merged into one: it still
  // answers "already known" for a comparison that marks an old range again, and keeps the
  // list short on a route driven again and again.
  std::pair<int64_t, int64_t> old{INT64_MAX, INT64_MIN};
  std::vector<std::pair<int64_t, int64_t>> kept;
  for (const auto& range : full_ranges_) {
    if (range.second < first) {
      old.first = std::min(old.first, range.first);
      old.second = std::max(old.second, range.second);
    } else {
      kept.push_back(range);
    }
  }
  if (old.first != INT64_MAX) kept.insert(kept.begin(), old);
  full_ranges_ = std::move(kept);
}

bool RltPlane::InFullRange(int64_t iteration) const {
  return std::any_of(full_ranges_.begin(), full_ranges_.end(), [iteration](const auto& r) {
    return iteration >= r.first && iteration <= r.second;
  });
}

void RltPlane::Retire(double length) {
  // Every retired_stride_-th length is kept; when the sample is full, every other one goes and
  // the stride doubles, so the sample stays spread evenly over all the dropped sightings.
  if (retired_count_++ % retired_stride_ != 0) return;
  retired_lengths_.push_back(static_cast<float>(length));
  if (retired_lengths_.size() < static_cast<size_t>(options_.retired_lengths)) return;
  for (size_t i = 0; 2 * i < retired_lengths_.size(); ++i) {
    retired_lengths_[i] = retired_lengths_[2 * i];
  }
  retired_lengths_.resize((retired_lengths_.size() + 1) / 2);
  retired_stride_ *= 2;
}

size_t RltPlane::LowerBound(int64_t iteration) const {
  // Most look-ups are for the latest sightings (a comparison brought up to date each
  // iteration): those are answered without the search.
  const size_t n = observations_.size();
  if (n == 0 || observations_.back().iteration < iteration) return n;
  if (n == 1 || observations_[n - 2].iteration < iteration) return n - 1;
  auto it =
      std::lower_bound(observations_.begin(), observations_.end(), iteration,
                       [](const Observation& o, int64_t value) { return o.iteration < value; });
  return static_cast<size_t>(it - observations_.begin());
}

const Observation* RltPlane::At(int64_t iteration) const {
  const size_t i = LowerBound(iteration);
  if (i < observations_.size() && observations_[i].iteration == iteration) {
    return &observations_[i];
  }
  return nullptr;
}

int64_t RltPlane::PhaseAt(int64_t iteration) const {
  auto it = std::upper_bound(phase_starts_.begin(), phase_starts_.end(), iteration);
  if (it == phase_starts_.begin()) return phase_starts_.front() - 1;
  return *(it - 1);
}

double RltPlane::Length() const {
  if (full_ranges_.empty()) return max_length_;
  if (full_dirty_) {
    // Median visible length while seen whole: unbiased under noise, unlike the maximum, and
    // robust to the two ways a "whole" sighting misleads. Seen at a grazing angle from a few
    // metres, a short piece takes in points past its ends (a face can be seen over half as long
    // again), so a length near the longest sightings moves whatever is placed from the piece's
    // far end along the wall. And an edge cut by the range stays put while the sensor turns in
    // place, so it passes for a static edge: those sightings are short. Either kind is a
    // minority of the sightings.
    const size_t cap = static_cast<size_t>(options_.full_length_sightings);
    std::vector<double> lengths;
    capped_ = false;
    for (auto r = full_ranges_.rbegin(); r != full_ranges_.rend() && lengths.size() < cap; ++r) {
      for (size_t i = LowerBound(r->first); i < observations_.size() && lengths.size() < cap; ++i) {
        if (observations_[i].iteration > r->second) break;
        if (lengths.empty()) capped_from_ = observations_[i].iteration;
        lengths.push_back(observations_[i].Length());
      }
      if (r == full_ranges_.rbegin() && lengths.size() == cap) {
        capped_ = true;
        capped_first_ = r->first;
      }
    }
    // The sightings already dropped (bounded memory) count through their thinned sample, each
    // for the sightings it stands for: without them a plane seen whole again on a second lap
    // takes its length from that lap alone, and a run of short sightings there (the segmenter
    // giving a pilaster's corner to the wall beside it for a while) shortens the face, moves its
    // far end as much in every group that places it from the near one, and the pose graph
    // (§II.D) slides a whole leg of the loop across its hallway.
    std::vector<std::pair<double, double>> weighted;  // length, sightings it stands for
    weighted.reserve(lengths.size() + retired_lengths_.size());
    for (double l : lengths) weighted.emplace_back(l, 1.0);
    const double stride = static_cast<double>(retired_stride_);
    for (float l : retired_lengths_) weighted.emplace_back(l, stride);
    if (!weighted.empty()) {
      std::sort(weighted.begin(), weighted.end());
      double total = 0.0;
      for (const auto& w : weighted) total += w.second;
      double below = 0.0;
      for (const auto& [length, weight] : weighted) {
        below += weight;
        full_length_ = length;
        if (below > 0.5 * total) break;  // the upper median, as without a sample
      }
      full_valid_ = true;
    }
    full_dirty_ = false;
  }
  // Seen whole only in sightings already dropped, before any length was taken from them: the
  // maximum, as it grows (it no longer marks the full length for recomputing).
  return full_valid_ ? full_length_ : max_length_;
}

void RltPlane::MarkFull(int64_t first, int64_t last) {
  for (auto& range : full_ranges_) {
    if (first >= range.first && last <= range.second) return;  // nothing new
  }
  bool merged = false;
  for (auto& range : full_ranges_) {
    if (first <= range.second + 1 && last + 1 >= range.first) {
      const int64_t old_first = range.first;
      range.first = std::min(range.first, first);
      range.second = std::max(range.second, last);
      merged = true;
      // The newest range grown at its end only, when the full length was taken from its
      // first sightings alone (all still stored): those are the same, and so is the length.
      if (!full_dirty_ && capped_ && &range == &full_ranges_.back() && range.first == old_first &&
          old_first == capped_first_ && observations_.front().iteration <= capped_from_) {
        return;
      }
      break;
    }
  }
  if (!merged) full_ranges_.emplace_back(first, last);
  full_dirty_ = true;
}
double OrientationWeight(const RltPlane& plane) { return plane.BestOrientationWeight(); }

}  // namespace relplane::mapper
