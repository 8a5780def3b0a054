#include "relplane/mapper/rltplane.hpp"

#include <algorithm>

namespace relplane::mapper {
namespace {

constexpr double kFullLengthTolerance = 0.1;  // m, several times the edge noise

}  // namespace

RltPlane::RltPlane(int64_t id, Observation first, double phase_hysteresis, int max_observations)
    : id_(id),
      hysteresis_(phase_hysteresis),
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
  const double length = obs.Length();
  const int64_t it = obs.iteration;
  // §II.C growth tracking with hysteresis; the new phase starts just after the extreme so the
  // split is where the trend really turned, not where it was noticed.
  if (growing_) {
    if (length >= extreme_length_) {
      extreme_length_ = length;
      extreme_iteration_ = it;
    } else if (length < extreme_length_ - hysteresis_) {
      phase_starts_.push_back(extreme_iteration_ + 1);
      growing_ = false;
      extreme_length_ = length;
      extreme_iteration_ = it;
    }
  } else {
    if (length <= extreme_length_) {
      extreme_length_ = length;
      extreme_iteration_ = it;
    } else if (length > extreme_length_ + hysteresis_) {
      phase_starts_.push_back(extreme_iteration_ + 1);
      growing_ = true;
      extreme_length_ = length;
      extreme_iteration_ = it;
    }
  }
  if (length > max_length_) {
    max_length_ = length;
    full_dirty_ = !full_ranges_.empty();
  }
  z_min_ = std::min(z_min_, obs.z_min);
  z_max_ = std::max(z_max_, obs.z_max);
  observations_.push_back(std::move(obs));
  ++count_;
  while (observations_.size() > max_observations_) observations_.pop_front();
  // Phase starts older than the stored observations are no longer needed.
  while (phase_starts_.size() > 2 && phase_starts_[1] <= observations_.front().iteration) {
    phase_starts_.erase(phase_starts_.begin());
  }
}

size_t RltPlane::LowerBound(int64_t iteration) const {
  auto it = std::lower_bound(
      observations_.begin(), observations_.end(), iteration,
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
    // Mean visible length while seen whole: unbiased, unlike the maximum, under noise. A wall
    // is never seen longer than it is, so sightings well below the longest one were not whole
    // after all (an edge cut by the range stays put while the sensor turns in place and passes
    // for a static edge): they are left out.
    double sum = 0.0;
    int n = 0;
    for (auto r = full_ranges_.rbegin(); r != full_ranges_.rend() && n < 300; ++r) {
      for (size_t i = LowerBound(r->first); i < observations_.size() && n < 300; ++i) {
        if (observations_[i].iteration > r->second) break;
        if (observations_[i].Length() < max_length_ - kFullLengthTolerance) continue;
        sum += observations_[i].Length();
        ++n;
      }
    }
    full_length_ = n > 0 ? sum / n : max_length_;
    full_dirty_ = false;
  }
  return full_length_;
}

void RltPlane::MarkFull(int64_t first, int64_t last) {
  for (auto& range : full_ranges_) {
    if (first >= range.first && last <= range.second) return;  // nothing new
  }
  bool merged = false;
  for (auto& range : full_ranges_) {
    if (first <= range.second + 1 && last + 1 >= range.first) {
      range.first = std::min(range.first, first);
      range.second = std::max(range.second, last);
      merged = true;
      break;
    }
  }
  if (!merged) full_ranges_.emplace_back(first, last);
  full_dirty_ = true;
}
}  // namespace relplane::mapper
