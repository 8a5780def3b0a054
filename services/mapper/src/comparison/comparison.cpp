#include "comparison/comparison.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

#include "plane_store/observation.hpp"
#include "relplane/common/geometry.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

Eigen::Matrix2d RotationT(double alpha) {
  const double c = std::cos(alpha), s = std::sin(alpha);
  Eigen::Matrix2d r;
  r << c, s, -s, c;  // R(alpha)^T
  return r;
}

}  // namespace

ObservationTerms ComparisonTerms(const Observation& obs, const FitOptions& fit) {
  ObservationTerms t;
  t.alpha = obs.Alpha();
  t.rotation_t = RotationT(t.alpha);
  t.weight = OrientationWeight(obs, fit);
  t.blur = PieceBlur(obs, fit);
  return t;
}

namespace {

// Adds one iteration's untransformed pair to the sub-interval's sums (§II.C algorithm: "rotate
// both planes so rltplane 1 is at 0 degrees, add the dx dy to L_av, the orientation to O_av").
// ta, tb: the observations' terms (ComparisonTerms).
void AddSample(const Observation& oa, const ObservationTerms& ta, const Observation& ob,
               const ObservationTerms& tb, SubInterval* s) {
  const double alpha_a = ta.alpha, alpha_b = tb.alpha;
  const double dalpha = geometry::WrapAngle(alpha_b - alpha_a);
  s->n += 1.0;
  s->sin_sum += std::sin(dalpha);
  s->cos_sum += std::cos(dalpha);
  // The difference's variance is the sum of both fits' orientation variances: an iteration
  // where one plane is a short piece (a door jamb, a wall the view cuts to a sliver) counts
  // for little.
  const double w = 1.0 / (1.0 / ta.weight + 1.0 / tb.weight);
  s->wsin_sum += w * std::sin(dalpha);
  s->wcos_sum += w * std::cos(dalpha);
  s->information += w;
  const double pa = ta.blur, pb = tb.blur;
  const double wp = 1.0 / (1.0 / ta.weight + 1.0 / tb.weight + pa * pa + pb * pb);
  s->psin_sum += wp * std::sin(dalpha);
  s->pcos_sum += wp * std::cos(dalpha);
  s->piece_information += wp;
  const Eigen::Matrix2d& rat = ta.rotation_t;
  const Eigen::Matrix2d& rbt = tb.rotation_t;
  const Vector2d nb_in_a = rat * ob.normal, na_in_b = rbt * oa.normal;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      // An edge cut by the view now is no wall end now: the pairing skips this sample.
      if (oa.ViewCut(i) || ob.ViewCut(j)) continue;
      const Vector2d ab = rat * (ob.edge[j] - oa.edge[i]);  // B's edge j from A's edge i
      const Vector2d ba = rbt * (oa.edge[i] - ob.edge[j]);  // A's edge i from B's edge j
      s->npair[i][j] += 1.0;
      for (int k = 0; k < 2; ++k) {
        const Vector2d& in_view = k == 0 ? oa.edge[i] : ob.edge[j];
        double* e = s->pair_edges[i][j][k];
        e[0] += in_view.x(), e[1] += in_view.y();
        e[2] += in_view.x() * in_view.x(), e[3] += in_view.y() * in_view.y();
      }
      double* p = s->pair[0][i][j];
      p[0] += ab.x(), p[1] += ab.y(), p[2] += ab.x() * ab.x(), p[3] += ab.y() * ab.y();
      double* q = s->pair[1][j][i];
      q[0] += ba.x(), q[1] += ba.y(), q[2] += ba.x() * ba.x(), q[3] += ba.y() * ba.y();
    }
    const double ca = nb_in_a.dot(rat * (ob.edge[0] - oa.edge[i]));
    s->line[0][i][0] += ca, s->line[0][i][1] += ca * ca;
    const double cb = na_in_b.dot(rbt * (oa.edge[0] - ob.edge[i]));
    s->line[1][i][0] += cb, s->line[1][i][1] += cb * cb;
  }
  s->cut[0] += oa.ViewCut(0), s->cut[1] += oa.ViewCut(1);
  s->cut[2] += ob.ViewCut(0), s->cut[3] += ob.ViewCut(1);
  const Vector2d pts[4] = {oa.edge[0], oa.edge[1], ob.edge[0], ob.edge[1]};
  for (int k = 0; k < 4; ++k) {
    double* e = s->edges[k];
    e[0] += pts[k].x(), e[1] += pts[k].y();
    e[2] += pts[k].x() * pts[k].x(), e[3] += pts[k].y() * pts[k].y();
  }
}

// Which edges of the observation at index k are cut by the view, by the majority of the three
// around it: a single flicker of the flag under noise does not count.
int CutKey(const std::deque<Observation>& obs, size_t k, size_t size) {
  int key = 0;
  for (int e = 0; e < 2; ++e) {
    int votes = 0, total = 0;
    for (size_t q = k > 0 ? k - 1 : 0; q <= k + 1 && q < size; ++q)
      votes += obs[q].ViewCut(e), ++total;
    if (2 * votes > total) key |= 1 << e;
  }
  return key;
}

double Std2(const double* sums, double n) {
  const double vx = sums[2] / n - (sums[0] / n) * (sums[0] / n);
  const double vy = sums[3] / n - (sums[1] / n) * (sums[1] / n);
  return std::sqrt(std::max(0.0, vx) + std::max(0.0, vy));
}

double Std1(const double* sums, double n) {
  return std::sqrt(std::max(0.0, sums[1] / n - (sums[0] / n) * (sums[0] / n)));
}

// §II.C static edges: of the four pairings the one with the lowest standard deviation pairs the
// static edges. Every pairing under the threshold is static (a wall seen whole has two).
// Parallel planes across from each other can show a static-static and a dynamic-dynamic pairing
// that are both steady: without other information the two cannot be told apart, so such a
// sub-interval gives no location along the walls (the reordering in relative_map.cpp then
// reaches these planes through other comparisons).
StaticVerdict Judge(const SubInterval& s, const ComparisonOptions& options) {
  StaticVerdict v;
  const double n = s.n;
  const double dalpha = std::atan2(s.sin_sum, s.cos_sum);
  const bool parallel = std::abs(std::sin(dalpha)) < std::sin(options.parallel_angle);
  if (n < options.min_samples) {
    // Too short to judge edges on, but a parallel line's offset does not depend on where the
    // edges are: kept aside where steady (DirectedStats::short_line_sum). One sample shows no
    // steadiness.
    if (!parallel || n < 2) return v;
    for (int dir = 0; dir < 2; ++dir) {
      for (int i = 0; i < 2; ++i) {
        if (Std1(s.line[dir][i], n) > options.static_std) continue;
        v.stats[dir].short_line_sum[i] += s.line[dir][i][0];
        v.stats[dir].short_line_sq[i] += s.line[dir][i][1];
        v.stats[dir].short_line_count[i] += n;
      }
    }
    return v;
  }
  double motion = 0.0;
  for (const auto& e : s.edges) motion = std::max(motion, Std2(e, n));
  // Lines are steady whether or not the sensor moves relative to their edges.
  for (int dir = 0; dir < 2; ++dir) {
    for (int i = 0; i < 2; ++i) {
      // A crossing line is placed along the wall from its edge i: an edge the view cuts (a
      // jamb's occlusion, a door opening a wall seen whole) is no wall end, however still it
      // stands, and is not where the wall's end is mapped. A parallel line's offset does not
      // depend on where along the wall the edge is.
      if (!parallel && s.cut[2 * dir + i] > (1.0 - options.uncut_share) * n) continue;
      if (Std1(s.line[dir][i], n) <= options.static_std &&
          (motion >= options.min_motion || parallel)) {
        v.stats[dir].line_sum[i] += s.line[dir][i][0];
        v.stats[dir].line_sq[i] += s.line[dir][i][1];
        v.stats[dir].line_count[i] += n;
      }
    }
  }
  if (motion < options.min_motion) return v;  // a still sensor makes every edge look static
  double std_ij[2][2];
  int best_i = 0, best_j = 0;
  int low = 0;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      // Judged over the samples where neither edge was cut by the view; an edge cut in more
      // than a few of them is no wall end (a cut flag flickers under noise near the border,
      // so one cut sample does not condemn it, nor split the interval).
      const double m = s.npair[i][j];
      // Two edges that both stood still in the view keep their relative position whatever
      // they are: a static edge moves in the view as the sensor does, while ends that ride
      // along with it (a wall's end at the range limit, a segmentation split at a set
      // distance) do not. Such a pairing tells nothing, as with a still sensor above.
      const bool moved = m > 0.0 && std::max(Std2(s.pair_edges[i][j][0], m),
                                             Std2(s.pair_edges[i][j][1], m)) >= options.min_motion;
      std_ij[i][j] = moved && m >= options.min_samples && m >= options.uncut_share * n
                         ? Std2(s.pair[0][i][j], m)
                         : 1e9;
      if (std_ij[i][j] < std_ij[best_i][best_j]) best_i = i, best_j = j;
      if (std_ij[i][j] <= options.static_std) ++low;
    }
  }
  if (std_ij[best_i][best_j] > options.static_std) return v;
  // Pairings close to the best one are static too; one far above it has a slowly moving edge
  // (e.g. an edge occluded by a door jamb), however small its spread.
  const double threshold =
      std::min(options.static_std,
               std::max(options.static_floor, options.static_ratio * std_ij[best_i][best_j]));
  low = 0;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) low += std_ij[i][j] <= threshold ? 1 : 0;
  }
  if (parallel && low == 2 && std_ij[1 - best_i][1 - best_j] <= threshold) {
    v.ambiguous = true;
    return v;
  }
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      if (std_ij[i][j] > threshold) continue;
      v.static_a[i] = v.static_b[j] = true;
      const double m = s.npair[i][j];
      v.stats[0].pair_sum[i][j] += Vector2d(s.pair[0][i][j][0], s.pair[0][i][j][1]);
      v.stats[0].pair_count[i][j] += m;
      v.stats[0].pair_sq[i][j] += s.pair[0][i][j][2] + s.pair[0][i][j][3];
      v.stats[1].pair_sq[j][i] += s.pair[1][j][i][2] + s.pair[1][j][i][3];
      v.stats[1].pair_sum[j][i] += Vector2d(s.pair[1][j][i][0], s.pair[1][j][i][1]);
      v.stats[1].pair_count[j][i] += m;
    }
  }
  return v;
}

// Judge's verdict on `s`, kept in it until its sums change.
const StaticVerdict& Judged(SubInterval& s, const ComparisonOptions& options) {
  if (!s.judged) {
    s.verdict = Judge(s, options);
    s.judged = true;
  }
  return s.verdict;
}

}  // namespace

DirectedStats::DirectedStats() {
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      pair_sum[i][j].setZero();
      pair_sq[i][j] = 0.0;
      pair_count[i][j] = 0.0;
    }
    line_sum[i] = 0.0;
    line_sq[i] = 0.0;
    line_count[i] = 0.0;
    short_line_sum[i] = 0.0;
    short_line_sq[i] = 0.0;
    short_line_count[i] = 0.0;
  }
}

void DirectedStats::Add(const DirectedStats& other) {
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      pair_sum[i][j] += other.pair_sum[i][j];
      pair_sq[i][j] += other.pair_sq[i][j];
      pair_count[i][j] += other.pair_count[i][j];
    }
    line_sum[i] += other.line_sum[i];
    line_sq[i] += other.line_sq[i];
    line_count[i] += other.line_count[i];
    short_line_sum[i] += other.short_line_sum[i];
    short_line_sq[i] += other.short_line_sq[i];
    short_line_count[i] += other.short_line_count[i];
  }
}

bool DirectedStats::Pair(int i, int j, Eigen::Vector2d* mean) const {
  if (pair_count[i][j] <= 0.0) return false;
  *mean = pair_sum[i][j] / pair_count[i][j];
  return true;
}

double DirectedStats::PairStd(int i, int j) const {
  if (pair_count[i][j] <= 0.0) return 0.0;
  const Eigen::Vector2d mean = pair_sum[i][j] / pair_count[i][j];
  return std::sqrt(std::max(0.0, pair_sq[i][j] / pair_count[i][j] - mean.squaredNorm()));
}

double DirectedStats::LineStd(int i) const {
  const bool judged = line_count[i] > 0.0;
  const double count = judged ? line_count[i] : short_line_count[i];
  if (count <= 0.0) return 0.0;
  const double mean = (judged ? line_sum[i] : short_line_sum[i]) / count;
  return std::sqrt(std::max(0.0, (judged ? line_sq[i] : short_line_sq[i]) / count - mean * mean));
}

double DirectedStats::LineCount(int i) const {
  return line_count[i] > 0.0 ? line_count[i] : short_line_count[i];
}

bool DirectedStats::Line(int i, const ComparisonOptions& options, double* mean) const {
  if (line_count[i] > 0.0) {
    // Steady in each sub-interval at offsets that spread over them more than one may: two
    // surfaces, no line (as a static pairing's sub-intervals, §II.C).
    if (LineStd(i) > options.static_std) return false;
    *mean = line_sum[i] / line_count[i];
    return true;
  }
  if (short_line_count[i] < options.min_samples || LineStd(i) > options.pooled_std) return false;
  *mean = short_line_sum[i] / short_line_count[i];
  return true;
}

void Comparison::Update(RltPlane& a, RltPlane& b, int64_t now, const ComparisonOptions& options,
                        int max_gap) {
  Rebuild(a, b, now, options, max_gap);
  Summarise(a, b, now, options);
}

void Comparison::Rebuild(RltPlane& a, RltPlane& b, int64_t now, const ComparisonOptions& options,
                         int max_gap) {
  // A growth phase that started in the past (found with some lag) re-splits the open
  // sub-intervals from that iteration on.
  int64_t redo_from = INT64_MAX;
  if (phase_seen_a_ != a.LatestPhaseStart()) redo_from = std::min(redo_from, a.LatestPhaseStart());
  if (phase_seen_b_ != b.LatestPhaseStart()) redo_from = std::min(redo_from, b.LatestPhaseStart());
  phase_seen_a_ = a.LatestPhaseStart();
  phase_seen_b_ = b.LatestPhaseStart();
  if (redo_from != INT64_MAX && redo_from < processed_until_) {
    while (!open_.empty() && open_.back().last >= redo_from) open_.pop_back();
    if (open_.size() < prefix_count_) prefix_count_ = 0;  // its sums hold the ones dropped
    processed_until_ = open_.empty() ? frozen_until_ : open_.back().last + 1;
  }
  // Walk the common iterations not yet summed.
  const auto& obs_a = a.Observations();
  const auto& obs_b = b.Observations();
  size_t ia = a.LowerBound(processed_until_), ib = b.LowerBound(processed_until_);
  while (ia < obs_a.size() && ib < obs_b.size()) {
    const int64_t ka = obs_a[ia].iteration, kb = obs_b[ib].iteration;
    if (ka < kb) {
      ++ia;
      continue;
    }
    if (kb < ka) {
      ++ib;
      continue;
    }
    const int64_t pa = a.PhaseAt(ka), pb = b.PhaseAt(ka);
    // Also split where an edge stays cut by the view or stops being cut for a while: its
    // static state changes. A single flicker does not split (see Judge).
    const int cut_key = CutKey(obs_a, ia, a.Observations().size()) |
                        CutKey(obs_b, ib, b.Observations().size()) << 2;
    const bool extend = !open_.empty() && open_.back().phase_a == pa &&
                        open_.back().phase_b == pb && open_.back().cut_key == cut_key &&
                        ka - open_.back().last <= max_gap &&
                        open_.back().n < options.max_subinterval;
    if (!extend) {
      SubInterval s;
      s.first = ka;
      s.phase_a = pa;
      s.phase_b = pb;
      s.cut_key = cut_key;
      open_.push_back(s);
    }
    open_.back().last = ka;
    open_.back().judged = false;
    if (open_.size() - 1 < prefix_count_) prefix_count_ = 0;  // its sums hold this one's
    AddSample(obs_a[ia], a.Terms(ia), obs_b[ib], b.Terms(ib), &open_.back());
    ++ia;
    ++ib;
  }
  processed_until_ = std::max(processed_until_, now + 1);
  // Freeze sub-intervals that can no longer be re-split.
  while (open_.size() > 1 && open_.front().last < now - options.freeze_lag) {
    SubInterval& s = open_.front();
    AddTo(s, options, &frozen_);
    frozen_until_ = s.last + 1;
    open_.erase(open_.begin());
    prefix_count_ = 0;
  }
}

void Comparison::AddTo(SubInterval& s, const ComparisonOptions& options, Sums* sums) {
  const StaticVerdict& v = Judged(s, options);
  sums->total[0].Add(v.stats[0]);
  sums->total[1].Add(v.stats[1]);
  sums->n += s.n;
  sums->wsin += s.wsin_sum;
  sums->wcos += s.wcos_sum;
  sums->information += s.information;
  sums->psin += s.psin_sum;
  sums->pcos += s.pcos_sum;
  sums->piece_information += s.piece_information;
  sums->ambiguous += v.ambiguous ? 1 : 0;
}

void Comparison::Summarise(RltPlane& a, RltPlane& b, int64_t now,
                           const ComparisonOptions& options) {
  if (prefix_count_ == 0) prefix_ = frozen_;
  for (; prefix_count_ + 1 < open_.size(); ++prefix_count_) {
    AddTo(open_[prefix_count_], options, &prefix_);
  }
  sums_ = prefix_;
  if (prefix_count_ < open_.size()) AddTo(open_.back(), options, &sums_);
  for (SubInterval& s : open_) {
    const StaticVerdict& v = Judged(s, options);
    if (v.static_a[0] && v.static_a[1]) a.MarkFull(s.first, s.last);
    if (v.static_b[0] && v.static_b[1]) b.MarkFull(s.first, s.last);
    if (s.last == now) {  // the interval that includes this iteration: edges static now
      for (int e = 0; e < 2; ++e) {
        a.static_now[e] = a.static_now[e] || v.static_a[e];
        b.static_now[e] = b.static_now[e] || v.static_b[e];
      }
    }
  }
  delta_alpha_ = std::atan2(sums_.wsin, sums_.wcos);
  piece_alpha_ = std::atan2(sums_.psin, sums_.pcos);
}

}  // namespace relplane::mapper
