#include "relplane/mapper/relative_map.hpp"

#include <algorithm>
#include <cmath>

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

constexpr double kSpreadScale = 0.005;  // m

Eigen::Matrix2d Rot(double a) { return Eigen::Rotation2Dd(a).toRotationMatrix(); }

// B's edge j seen from A's edge i, also through the other edge of a wall seen whole.
bool PairThrough(const Comparison& c, const RltPlane& a, int i, int* j, Vector2d* delta,
                 double* weight) {
  const DirectedStats& s = c.From(a.Id());
  *weight = 0.0;
  for (int ii = 0; ii < 2; ++ii) {
    if (ii != i && !a.FullLengthKnown()) continue;
    for (int jj = 0; jj < 2; ++jj) {
      // Quality of a pairing: its iterations, discounted by its spread over the whole interval.
      const double spread = s.PairStd(ii, jj) / kSpreadScale;
      // Through the other edge only when no direct pairing is as good: the full length adds
      // its own error.
      const double w = s.pair_count[ii][jj] / (1.0 + spread * spread) * (ii == i ? 1.0 : 0.5);
      if (w <= *weight) continue;
      Vector2d d = s.pair_sum[ii][jj] / s.pair_count[ii][jj];
      // e_hi = e_lo + L t: move from edge ii to edge i of A (in A's frame t = x axis).
      d -= static_cast<double>(i - ii) * a.Length() * Vector2d::UnitX();
      *delta = d;
      *j = jj;
      *weight = w;
    }
  }
  return *weight > 0.0;
}

}  // namespace

bool EdgePoint(const RltPlane& plane, const Placement& placement, int edge, Vector2d* point) {
  if (placement.known != Known::kPoint) return false;
  if (placement.ref == edge) {
    *point = placement.point;
    return true;
  }
  if (placement.has_other) {
    *point = placement.other;
    return true;
  }
  if (!plane.FullLengthKnown()) return false;
  const double sign = edge == 1 ? 1.0 : -1.0;
  *point = placement.point + sign * plane.Length() * DirectionOf(placement.alpha);
  return true;
}

RelativeMap BuildRelativeMap(const Group& group, MapperState& state) {
  RelativeMap map;
  const auto& members = group.members;
  if (members.empty()) return map;
  // Basis and its reference edge: the most static-pairing evidence (§II.F reordering).
  double best = -1.0;
  int basis_ref = -1;
  for (int64_t m : members) {
    double count[2] = {0.0, 0.0};
    for (int64_t o : members) {
      if (o == m) continue;
      const Comparison* c = state.FindComparison(m, o);
      if (c == nullptr) continue;
      count[0] += c->From(m).PairCount(0);
      count[1] += c->From(m).PairCount(1);
    }
    const double total = count[0] + count[1];
    if (total > best) {
      best = total;
      map.basis = m;
      basis_ref = total > 0.0 ? (count[1] > count[0] ? 1 : 0) : -1;
    }
  }
  Placement basis;
  basis.ref = basis_ref;
  basis.known = basis_ref >= 0 ? Known::kPoint : Known::kLine;
  map.members[map.basis] = basis;

  // Prim's algorithm over static pairings: repeatedly attach the unplaced member with the
  // strongest static pairing to a member placed with a point.
  struct Candidate {
    double weight = 0.0;
    int64_t from = -1;
    int j = -1;
    Vector2d delta = Vector2d::Zero();
  };
  std::map<int64_t, Candidate> candidates;
  auto relax = [&](int64_t from) {
    const Placement& p = map.members[from];
    if (p.known != Known::kPoint) return;
    const RltPlane& a = *state.Plane(from);
    for (int64_t to : members) {
      if (map.members.count(to)) continue;
      const Comparison* c = state.FindComparison(from, to);
      if (c == nullptr) continue;
      Candidate cand;
      cand.from = from;
      if (PairThrough(*c, a, p.ref, &cand.j, &cand.delta, &cand.weight) &&
          cand.weight > candidates[to].weight) {
        candidates[to] = cand;
      }
    }
  };
  relax(map.basis);
  while (true) {
    int64_t to = -1;
    double weight = 0.0;
    for (const auto& [id, cand] : candidates) {
      if (cand.weight > weight && !map.members.count(id)) to = id, weight = cand.weight;
    }
    if (to < 0) break;
    const Candidate cand = candidates[to];
    const Placement& from = map.members[cand.from];
    const Comparison& c = *state.FindComparison(cand.from, to);
    Placement q;
    q.alpha = from.alpha + c.DeltaAlpha(cand.from);
    q.point = from.point + Rot(from.alpha) * cand.delta;
    q.ref = cand.j;
    q.known = Known::kPoint;
    map.members[to] = q;
    candidates.erase(to);
    relax(to);
  }
  // Lines: a member whose line is steady relative to a placed edge (or parallel to a placed
  // line) is placed on that line.
  for (bool changed = true; changed;) {
    changed = false;
    for (int64_t to : members) {
      if (map.members.count(to)) continue;
      for (const auto& [from, p] : map.members) {
        const Comparison* c = state.FindComparison(from, to);
        if (c == nullptr) continue;
        const DirectedStats& s = c->From(from);
        const double dalpha = c->DeltaAlpha(from);
        const bool parallel = std::abs(std::sin(dalpha)) < 0.17;
        double offset = 0.0;
        bool ok = false;
        if (p.known == Known::kPoint && s.Line(p.ref, &offset)) ok = true;
        if (!ok && p.known == Known::kLine && parallel &&
            (s.Line(0, &offset) || s.Line(1, &offset))) {
          ok = true;
        }
        if (!ok) continue;
        Placement q;
        q.alpha = p.alpha + dalpha;
        q.point = p.point + Rot(p.alpha) * (offset * NormalOf(dalpha));
        q.known = Known::kLine;
        map.members[to] = q;
        changed = true;
        break;
      }
    }
  }
  // Orientation only, through any comparison.
  for (int64_t to : members) {
    if (map.members.count(to)) continue;
    for (const auto& [from, p] : map.members) {
      const Comparison* c = state.FindComparison(from, to);
      if (c == nullptr || c->Common() <= 0.0) continue;
      Placement q;
      q.alpha = p.alpha + c->DeltaAlpha(from);
      q.point = p.point;
      q.known = Known::kAngle;
      map.members[to] = q;
      break;
    }
  }
  return map;
}

}  // namespace relplane::mapper
