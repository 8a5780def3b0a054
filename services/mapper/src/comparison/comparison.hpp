#pragma once
// §II.C Plane relative comparisons: two rltplanes seen in the same interval are rotated into the
// first plane's basis each iteration, so their relative location and orientation are rotation-
// and translation-invariant, and averaged over the common interval. Static edges are found by
// the four pairings of the two planes' edges with the lowest standard deviation; the interval is
// split where either plane turns from growing to shrinking.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "plane_store/rltplane.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// What one plane (B) looks like from another (A), averaged: in A's frame with its origin at one
// of A's edges (x along A's wall, y along A's normal).
struct DirectedStats {
  // Static pairings: B's edge j relative to A's edge i, summed over the sub-intervals where
  // the pairing was static (§II.C, Fig. 4).
  Eigen::Vector2d pair_sum[2][2];
  double pair_sq[2][2];  // sum of squared norms, for the spread over the whole interval
  double pair_count[2][2];
  // B's line offset from A's edge i (n_B . (p - e_Ai) for p on B), over sub-intervals where
  // it was steady: pins B's line even when none of B's edges is static.
  double line_sum[2];
  double line_sq[2];  // sum of squares, for the spread over all the steady sub-intervals
  double line_count[2];
  // The same for a parallel B over sub-intervals too short to judge edges on, pooled. A door
  // jamb's length flickers and each turn from growing to shrinking splits the interval (§II.C):
  // no sub-interval reached ComparisonOptions::min_samples, and a hallway's end wall, parallel to
  // the jamb 3 m before it, was placed instead from a far wall end 3.3 cm short (the segmenter's
  // last column at a grazing angle), with the hallway's next leg 3.5 cm off. Read only where no
  // judged sub-interval gave B's line, over ComparisonOptions::min_samples in all, and only if
  // the pieces agree to within ComparisonOptions::pooled_std (a recess's back wall taken for the
  // jamb for a few iterations
  // is steady on its own).
  double short_line_sum[2];
  double short_line_sq[2];
  double short_line_count[2];

  DirectedStats();
  void Add(const DirectedStats& other);
  bool Pair(int i, int j, Eigen::Vector2d* mean) const;
  // Standard deviation of a static pairing over all its sub-intervals together: an edge that
  // drifts slowly (occlusion) passes in each sub-interval but not over the whole interval.
  double PairStd(int i, int j) const;
  bool Line(int i, const ComparisonOptions& options, double* mean) const;
  // The samples behind Line(i) and their standard deviation over all its sub-intervals
  // together (sub-intervals each steady at different offsets: two surfaces, not one line).
  double LineCount(int i) const;
  double LineStd(int i) const;
  double PairCount(int i) const { return pair_count[i][0] + pair_count[i][1]; }
};

// What a sub-interval's sums say (§II.C): its static pairings and steady lines as sums to add
// to the comparison's totals, whether it was dropped as ambiguous, which edges were static.
struct StaticVerdict {
  DirectedStats stats[2];
  bool ambiguous = false;
  bool static_a[2] = {false, false};
  bool static_b[2] = {false, false};
};

// Running sums of one sub-interval (constant growth phase of both planes, no gap).
struct SubInterval {
  int64_t first = 0;
  int64_t last = 0;
  int64_t phase_a = 0;
  int64_t phase_b = 0;
  int cut_key = 0;  // which of the four edges are cut by the view (constant in a sub-interval)
  double n = 0.0;
  double sin_sum = 0.0;
  double cos_sum = 0.0;
  // The orientation difference weighted by each sample's information (both fits' orientation
  // variances), and that information.
  double wsin_sum = 0.0;
  double wcos_sum = 0.0;
  double information = 0.0;
  // The same with each fit's bias added to its variance (see Comparison::PieceAlpha).
  double psin_sum = 0.0;
  double pcos_sum = 0.0;
  double piece_information = 0.0;
  // [0]: B seen from A, [1]: A seen from B. Per pairing: x, y, x^2, y^2 sums.
  double pair[2][2][2][4] = {};
  double npair[2][2] = {};    // samples of pairing [i][j] where neither edge was cut
  double line[2][2][2] = {};  // [dir][edge][sum, sum^2]
  // Sensor-frame positions of A's and B's edges (x, y, x^2, y^2): did the sensor move at all?
  double edges[4][4] = {};
  // The same for the two edges of pairing [i][j] ([0]: A's edge i, [1]: B's edge j), over the
  // pairing's samples: did those two edges move in the view?
  double pair_edges[2][2][2][4] = {};
  int cut[4] = {0, 0, 0, 0};  // samples where A's edges 0, 1 and B's edges 0, 1 were cut
  // The verdict on these sums, kept until a sample is added: the open sub-intervals are summed
  // up at every iteration, and judging each of them again took a tenth of an iteration.
  bool judged = false;
  StaticVerdict verdict;
};

// The terms of one observation (RltPlane keeps them with its observations).
ObservationTerms ComparisonTerms(const Observation& obs, const FitOptions& fit);

class Comparison {
 public:
  Comparison(int64_t a, int64_t b) : a_(a), b_(b) {}

  // Brings the comparison up to iteration `now` from the planes' stored observations (§II.C).
  // Marks the edges found static in the interval that includes `now` on the planes, and marks a
  // plane seen whole where both its edges were static.
  void Update(RltPlane& a, RltPlane& b, int64_t now, const ComparisonOptions& options, int max_gap);

  int64_t A() const { return a_; }
  int64_t B() const { return b_; }
  int64_t Other(int64_t id) const { return id == a_ ? b_ : a_; }
  // The other plane as seen from plane `from` (which must be A() or B()).
  const DirectedStats& From(int64_t from) const {
    return from == a_ ? sums_.total[0] : sums_.total[1];
  }
  // Frame angle of the other plane minus that of `from`: the orientation difference averaged
  // over the common interval, each iteration weighted by how well both fits fix it.
  double DeltaAlpha(int64_t from) const { return from == a_ ? delta_alpha_ : -delta_alpha_; }
  // Information (rad^-2) of DeltaAlpha: the sum of the iterations' weights.
  double Information() const { return sums_.information; }
  // The orientation difference and its information with each fit's bias over its length added
  // to each iteration's variance: a short piece's fit is off by up to a few centimetres over its
  // length (a piece beside a jamb takes some of the jamb's points), which its noise alone does
  // not say. Added per iteration, not once per comparison: once, every comparison's weight would
  // be its pieces' bias alone, whatever the length of its interval (a comparison of two walls
  // over 5 iterations weighed as one over 500).
  double PieceAlpha(int64_t from) const { return from == a_ ? piece_alpha_ : -piece_alpha_; }
  double PieceInformation() const { return sums_.piece_information; }
  // Iterations in the common interval so far.
  double Common() const { return sums_.n; }
  // Sub-intervals dropped as ambiguous (§II.C parallel planes) so far.
  int Ambiguous() const { return sums_.ambiguous; }

 private:
  void Rebuild(RltPlane& a, RltPlane& b, int64_t now, const ComparisonOptions& options,
               int max_gap);
  void Summarise(RltPlane& a, RltPlane& b, int64_t now, const ComparisonOptions& options);
  struct Sums;
  // Adds sub-interval `s` (judged now if it was not since it changed) to `sums`.
  static void AddTo(SubInterval& s, const ComparisonOptions& options, Sums* sums);

  int64_t a_;
  int64_t b_;
  // Sums over sub-intervals (each one's verdict and orientation sums), added in their order.
  struct Sums {
    DirectedStats total[2];
    double n = 0.0;
    double wsin = 0.0;
    double wcos = 0.0;
    double information = 0.0;
    double psin = 0.0;
    double pcos = 0.0;
    double piece_information = 0.0;
    int ambiguous = 0;
  };
  // Frozen sub-intervals are folded into these sums and never recomputed (bounded cost).
  Sums frozen_;
  int64_t frozen_until_ = INT64_MIN;
  std::vector<SubInterval> open_;
  // The frozen sums plus those of the first `prefix_count_` open sub-intervals, kept while
  // those sub-intervals stay as they are: only the last one grows at an iteration, and adding
  // up every open one again at every update cost a tenth of the comparisons' time.
  Sums prefix_;
  size_t prefix_count_ = 0;
  int64_t processed_until_ = INT64_MIN;
  int64_t phase_seen_a_ = INT64_MIN;  // latest phase start of each plane at the last update
  int64_t phase_seen_b_ = INT64_MIN;
  Sums sums_;  // over the whole common interval
  // atan2 of the orientation sums, worked out once per update: the relative maps ask for them
  // for every pairing of every build.
  double delta_alpha_ = 0.0;
  double piece_alpha_ = 0.0;
};

}  // namespace relplane::mapper
