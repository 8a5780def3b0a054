#include "global_map/relative_map.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <set>

#include "global_map/relative_refine.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

Eigen::Matrix2d Rot(double a) { return Eigen::Rotation2Dd(a).toRotationMatrix(); }

// B's edge j seen from A's edge i, also through the other edge of a wall seen whole.
bool PairThrough(const Comparison& c, const RltPlane& a, int i, const ComparisonOptions& comparison,
                 int* j, Vector2d* delta, double* weight, double* variance) {
  const DirectedStats& s = c.From(a.Id());
  *weight = 0.0;
  for (int ii = 0; ii < 2; ++ii) {
    if (ii != i && !a.FullLengthKnown()) continue;
    for (int jj = 0; jj < 2; ++jj) {
      // A pairing whose static sub-intervals disagree by more than one may spread is no static
      // pairing over the whole interval (§II.C): the two edges did not keep one relative place.
      // Taken all the same where nothing better links the two walls, its mean is neither of
      // the places the edge was seen at (a pilaster's corner seen at two places along the
      // hallway), and the member and the pose with it stay there for the whole lap.
      if (s.PairStd(ii, jj) > comparison.static_std) continue;
      // Quality of a pairing: its iterations, discounted by its spread over the whole interval.
      const double spread = s.PairStd(ii, jj) / comparison.spread_scale;
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
      *variance = s.PairStd(ii, jj) * s.PairStd(ii, jj);
    }
  }
  return *weight > 0.0;
}

// The point placement of `to` from placed member `from` through their static pairing.
bool PlacePoint(const Placement& from_placed, int64_t from, int64_t to, const RelativeMapInputs& in,
                const ComparisonOptions& comparison, Placement* out, double* weight) {
  if (from_placed.known != Known::kPoint) return false;
  const Comparison* c = in.comparisons.Find(from, to);
  if (c == nullptr) return false;
  int j = -1;
  Vector2d delta;
  double variance = 0.0;
  if (!PairThrough(*c, *in.store.Plane(from), from_placed.ref, comparison, &j, &delta, weight,
                   &variance)) {
    return false;
  }
  out->alpha = from_placed.alpha + c->DeltaAlpha(from);
  out->point = from_placed.point + Rot(from_placed.alpha) * delta;
  out->ref = j;
  out->known = Known::kPoint;
  out->variance = from_placed.variance + variance;
  return true;
}

// The line placement of `to`: its line steady relative to a placed edge (or parallel to a
// placed line).
bool PlaceLine(const Placement& p, int64_t from, int64_t to, const RelativeMapInputs& in,
               const ComparisonOptions& comparison, Placement* out) {
  const Comparison* c = in.comparisons.Find(from, to);
  if (c == nullptr) return false;
  const DirectedStats& s = c->From(from);
  const double dalpha = c->DeltaAlpha(from);
  const bool parallel = std::abs(std::sin(dalpha)) < comparison.parallel_sin;
  double offset = 0.0;
  bool ok = p.known == Known::kPoint && s.Line(p.ref, comparison, &offset);
  // A parallel line's offset is the same from either edge, but its steadiness is not: each
  // sample measures it along the member's fitted normal, from where the edge is, and a short
  // face's fit turning a degree moves it centimetres at an edge metres away. A door recess's
  // back face metres along from the end wall's reference corner can be unsteady from there and
  // steady from the wall's other edge; judged from the reference edge alone it goes unplaced by
  // its parallel wall and is placed through a crossing wall's line from a few samples instead,
  // centimetres off.
  if (!ok && p.known == Known::kPoint && parallel) ok = s.Line(1 - p.ref, comparison, &offset);
  if (!ok && p.known == Known::kLine && parallel)
    ok = s.Line(0, comparison, &offset) || s.Line(1, comparison, &offset);
  if (!ok) return false;
  *out = Placement{};
  out->alpha = p.alpha + dalpha;
  out->point = p.point + Rot(p.alpha) * (offset * NormalOf(dalpha));
  out->known = Known::kLine;
  out->variance = p.variance;
  return true;
}

// Are `from` and `to` parallel by their comparison (the line placement then needs no edge)?
bool ParallelTo(int64_t from, int64_t to, const RelativeMapInputs& in,
                const ComparisonOptions& comparison) {
  const Comparison* c = in.comparisons.Find(from, to);
  return c != nullptr && std::abs(std::sin(c->DeltaAlpha(from))) < comparison.parallel_sin;
}

// The orientation of `to` only, through any comparison with a common interval.
bool PlaceAngle(const Placement& p, int64_t from, int64_t to, const RelativeMapInputs& in,
                Placement* out) {
  const Comparison* c = in.comparisons.Find(from, to);
  if (c == nullptr || c->Common() <= 0.0) return false;
  *out = Placement{};
  out->alpha = p.alpha + c->DeltaAlpha(from);
  out->point = p.point;
  out->known = Known::kAngle;
  return true;
}

// Members no point placement reached: by line where one is steady, else by orientation.
// Records the links used in `order` when given. A parallel member's line comes first: their
// offset is the difference of two fitted offsets, whereas a crossing member's line is measured
// from its edge, where that edge is seen. A corner's end is seen within a column spacing either
// side of the corner from frame to frame (the segmenter's wall-end estimate), centimetres at a
// few metres; a line taken from a crossing wall is off by that, whereas a wall parallel to it
// in the same group gives it within a fraction of a millimetre, and the pose and every wall
// placed after it follow the line. So: every line a parallel member gives, then one crossing
// line, and again.
void PlaceRest(const Group& group, const RelativeMapInputs& in, const ComparisonOptions& comparison,
               RelativeMap* map, ChainOrder* order) {
  auto place_lines = [&](bool parallel_only) {
    bool placed = false;
    for (int64_t to : group.members) {
      if (map->members.count(to)) continue;
      for (const auto& [from, p] : map->members) {
        Placement q;
        if (parallel_only && !ParallelTo(from, to, in, comparison)) continue;
        if (!PlaceLine(p, from, to, in, comparison, &q)) continue;
        map->members[to] = q;
        if (order != nullptr) order->links.push_back({from, to});
        placed = true;
        if (!parallel_only) return true;
        break;
      }
    }
    return placed;
  };
  while (place_lines(true) || place_lines(false)) {
  }
  for (int64_t to : group.members) {
    if (map->members.count(to)) continue;
    for (const auto& [from, p] : map->members) {
      Placement q;
      if (!PlaceAngle(p, from, to, in, &q)) continue;
      map->members[to] = q;
      if (order != nullptr) order->links.push_back({from, to});
      break;
    }
  }
}

RelativeMap StartAt(int64_t basis, int basis_ref) {
  RelativeMap map;
  map.basis = basis;
  Placement p;
  p.ref = basis_ref;
  p.known = basis_ref >= 0 ? Known::kPoint : Known::kLine;
  map.members[basis] = p;
  return map;
}

// Static-pairing evidence of member `m`'s two edges against the rest of the group.
double EdgeEvidence(const Group& group, const RelativeMapInputs& in, int64_t m, int* ref) {
  double count[2] = {0.0, 0.0};
  for (int64_t o : group.members) {
    if (o == m) continue;
    const Comparison* c = in.comparisons.Find(m, o);
    if (c == nullptr) continue;
    count[0] += c->From(m).PairCount(0);
    count[1] += c->From(m).PairCount(1);
  }
  const double total = count[0] + count[1];
  *ref = total > 0.0 ? (count[1] > count[0] ? 1 : 0) : -1;
  return total;
}

// Prim's algorithm over static pairings: repeatedly attach the unplaced member with the
// strongest static pairing to a member placed with a point. Records the links used in `order`
// when given.
void GrowByPoints(const Group& group, const RelativeMapInputs& in,
                  const ComparisonOptions& comparison, RelativeMap* map, ChainOrder* order) {
  struct Candidate {
    double weight = 0.0;
    int64_t from = -1;
    Placement placed;
  };
  std::map<int64_t, Candidate> candidates;
  auto relax = [&](int64_t from) {
    const Placement p = map->members[from];
    for (int64_t to : group.members) {
      if (map->members.count(to)) continue;
      Candidate cand;
      cand.from = from;
      if (PlacePoint(p, from, to, in, comparison, &cand.placed, &cand.weight) &&
          cand.weight > candidates[to].weight) {
        candidates[to] = cand;
      }
    }
  };
  relax(map->basis);
  while (true) {
    int64_t to = -1;
    double weight = 0.0;
    for (const auto& [id, cand] : candidates) {
      if (cand.weight > weight && !map->members.count(id)) to = id, weight = cand.weight;
    }
    if (to < 0) break;
    map->members[to] = candidates[to].placed;
    if (order != nullptr) order->links.push_back({candidates[to].from, to});
    candidates.erase(to);
    relax(to);
  }
}

// Does the chain reach a member whose static end an earlier group put on the global map?
bool LinksToMap(const RelativeMap& chain, const RelativeMapInputs& in, int64_t group_id) {
  for (const auto& [id, p] : chain.members) {
    const auto placed = in.world.global.find(id);
    const auto by = in.world.placed_by.find(id);
    if (placed != in.world.global.end() && placed->second.known == Known::kPoint &&
        by != in.world.placed_by.end() && by->second < group_id) {
      return true;
    }
  }
  return false;
}

// The basis and its reference edge among `candidates` (all members when empty): the most
// static-pairing evidence; the map grown from it by points, its links recorded in `order`.
RelativeMap GrowFromBest(const Group& group, const RelativeMapInputs& in,
                         const std::set<int64_t>& candidates, const ComparisonOptions& comparison,
                         ChainOrder* order) {
  double best = -1.0;
  order->basis = -1;
  order->basis_ref = -1;
  order->links.clear();
  for (int64_t m : group.members) {
    if (!candidates.empty() && candidates.count(m) == 0) continue;
    int ref = -1;
    const double total = EdgeEvidence(group, in, m, &ref);
    if (total > best) {
      best = total;
      order->basis = m;
      order->basis_ref = ref;
    }
  }
  RelativeMap map = StartAt(order->basis, order->basis_ref);
  GrowByPoints(group, in, comparison, &map, order);
  return map;
}

// The members after the point links: by line or orientation (PlaceRest), every orientation from
// all the comparisons, the points from all the static pairings. A line is placed from a placed
// member's point (a crossing wall's from its edge), so those members are placed again from the
// points as solved, and the orientations refined with them: a line left where the chain's point
// put it keeps that point's error. The points are solved once the orientations are refined
// (solved first, before PlaceRest on the chain's orientations, they were worse).
void PlaceTheRest(const Group& group, const RelativeMapInputs& in,
                  const ComparisonOptions& comparison, RelativeMap* map, ChainOrder* order) {
  PlaceRest(group, in, comparison, map, order);
  RefineOrientations(in, map);
  RefinePoints(in, comparison, map);
  RefineLines(in, comparison, map);
  for (auto it = map->members.begin(); it != map->members.end();) {
    const bool point = it->second.known == Known::kPoint || it->first == map->basis;
    it = point ? std::next(it) : map->members.erase(it);
  }
  if (order != nullptr) {
    auto& links = order->links;
    links.erase(std::remove_if(links.begin(), links.end(),
                               [&](const ChainLink& l) { return map->members.count(l.to) == 0; }),
                links.end());
  }
  PlaceRest(group, in, comparison, map, order);
  RefineOrientations(in, map);
}

// The comparison order that uses the most iterations (§II.F reordering) and the map it gives.
RelativeMap Choose(const Group& group, const RelativeMapInputs& in,
                   const ComparisonOptions& comparison, ChainOrder* order) {
  // The static pairings may form sets with no pairing between them: the chain from a basis
  // reaches its own set only, and the others are placed by lines. §II.D places a group through
  // the planes an earlier group placed, so the basis is in a set holding one whose static end
  // is on the global map, when there is such a set. By pairing evidence alone, whichever set it
  // is in, a small set (a two-wall corner) can take the basis over by an iteration's evidence and
  // leave the rest of the group placed along the hallway from its prior alone, and the rest of
  // the loop after it. The other members' chains are grown only when the best one's does not
  // link (growing every member's chain at every build costs several times the time per
  // iteration on a large map).
  RelativeMap map = GrowFromBest(group, in, {}, comparison, order);
  if (!LinksToMap(map, in, group.id)) {
    std::set<int64_t> linked;  // members whose chain reaches a static end on the global map
    for (int64_t m : group.members) {
      int ref = -1;
      if (m == order->basis || EdgeEvidence(group, in, m, &ref) <= 0.0) continue;
      RelativeMap chain = StartAt(m, ref);
      GrowByPoints(group, in, comparison, &chain, nullptr);
      if (LinksToMap(chain, in, group.id)) linked.insert(m);
    }
    if (!linked.empty()) map = GrowFromBest(group, in, linked, comparison, order);
  }
  PlaceTheRest(group, in, comparison, &map, order);
  return map;
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

ChainOrder ChooseOrder(const Group& group, const RelativeMapInputs& in,
                       const ComparisonOptions& comparison) {
  ChainOrder order;
  if (!group.members.empty()) Choose(group, in, comparison, &order);
  return order;
}

RelativeMap BuildRelativeMap(const Group& group, const RelativeMapInputs& in,
                             const ComparisonOptions& comparison) {
  const auto& members = group.members;
  if (members.empty()) return {};
  // A member that joined after the order was chosen is not in it: the order is chosen afresh
  // until the next evaluation.
  const ChainOrder& order = group.order;
  bool kept = order.basis >= 0;
  for (int64_t m : members) {
    kept = kept &&
           (m == order.basis || std::any_of(order.links.begin(), order.links.end(),
                                            [m](const ChainLink& link) { return link.to == m; }));
  }
  if (!kept) {
    ChainOrder fresh;
    return Choose(group, in, comparison, &fresh);
  }
  // §II.F: the order chosen at the reordering, with the comparisons' latest averages; a link
  // whose static pairing has gone falls back to the line, then the orientation.
  RelativeMap map = StartAt(order.basis, order.basis_ref);
  for (const ChainLink& link : order.links) {
    auto from = map.members.find(link.from);
    if (from == map.members.end() || map.members.count(link.to) ||
        std::find(members.begin(), members.end(), link.to) == members.end()) {
      continue;
    }
    const Placement p = from->second;
    Placement q;
    double weight = 0.0;
    if (PlacePoint(p, link.from, link.to, in, comparison, &q, &weight) ||
        PlaceLine(p, link.from, link.to, in, comparison, &q) ||
        PlaceAngle(p, link.from, link.to, in, &q)) {
      map.members[link.to] = q;
    }
  }
  PlaceTheRest(group, in, comparison, &map, nullptr);
  return map;
}

}  // namespace relplane::mapper
