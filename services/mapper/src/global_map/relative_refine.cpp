#include "global_map/relative_refine.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace relplane::mapper {

using Eigen::Vector2d;

namespace {

// The point-placed members of `map`, the basis first; false when the basis is not point-placed
// or no other member is.
bool PointPlaced(RelativeMap* map, std::vector<int64_t>* ids, std::vector<Placement*>* placed) {
  const auto basis = map->members.find(map->basis);
  if (basis == map->members.end() || basis->second.known != Known::kPoint) return false;
  *ids = {map->basis};
  *placed = {&basis->second};
  for (auto& [id, p] : map->members) {
    if (id == map->basis || p.known != Known::kPoint) continue;
    ids->push_back(id);
    placed->push_back(&p);
  }
  return ids->size() >= 2;
}

}  // namespace

// §II.D relative map: each member's orientation from all its comparisons with the others,
// weighted by their information, rather than along the one chain that placed it: a chain through
// a short piece beside a door (fitted degrees off as it shrinks to the jamb) turns the walls
// behind it by about a degree, while the piece on the door's other side is off the other way. The
// points stay where the chain put them: a link's offsets are in the frame of the member it starts
// from as that member was fitted then (placing them again along the chain with these
// orientations was tried and changed next to nothing).
void RefineOrientations(const RelativeMapInputs& in, RelativeMap* map) {
  // Least squares on the angles' corrections from the chain's values (within a few degrees of
  // the solution, so linear), the basis held: unknown k is member ids[k], the basis is last.
  std::vector<int64_t> ids;
  std::vector<Placement*> placed;
  for (auto& [id, p] : map->members) {
    if (id == map->basis) continue;
    ids.push_back(id);
    placed.push_back(&p);
  }
  const int n = static_cast<int>(ids.size());
  if (n == 0) return;
  ids.push_back(map->basis);
  placed.push_back(&map->members.at(map->basis));
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  for (int x = 0; x <= n; ++x) {
    for (int y = x + 1; y <= n; ++y) {
      const Comparison* cmp = in.comparisons.Find(ids[x], ids[y]);
      if (cmp == nullptr) continue;
      const double w = cmp->PieceInformation();
      if (w <= 0.0) continue;
      // Residual of theta_y - theta_x - delta at the chain's values.
      const double r =
          geometry::WrapAngle(placed[y]->alpha - placed[x]->alpha - cmp->PieceAlpha(ids[x]));
      // d(residual)/d(correction): +1 for y, -1 for x (the basis, index n, is held).
      if (y < n) a(y, y) += w, b(y) -= w * r;
      a(x, x) += w, b(x) += w * r;  // x < y <= n: never the basis
      if (y < n) a(x, y) -= w, a(y, x) -= w;
    }
  }
  // A member with no comparison keeps its chain value.
  for (int k = 0; k < n; ++k) {
    if (a(k, k) <= 0.0) a(k, k) = 1.0;
  }
  const Eigen::VectorXd dx = a.ldlt().solve(b);
  if (!dx.allFinite()) return;
  for (int k = 0; k < n; ++k) placed[k]->alpha = geometry::WrapAngle(placed[k]->alpha + dx(k));
}

// §II.D relative map: each point-placed member's reference edge from every static pairing among
// the point-placed members, by weighted least squares with the basis held, rather than along the
// one pairing the chain took for it. The chain takes the strongest pairing, but the candidates'
// weights are often within a few per cent of each other while what they say differs by
// centimetres: a short face's fit is turned by the neighbour's points at its creases, and what
// a pairing from it says is off by that turn times the lever. Their weighted mean spreads what any
// one of them is off. A pairing's weight is the chain's: its samples over (1 + (its spread /
// 5 mm)^2), the information of its mean with a 5 mm floor per sample; through a wall's length
// (seen whole) half, as in the chain. The orientations are held at RefineOrientations' values:
// the offsets stay linear in the points.
void RefinePoints(const RelativeMapInputs& in, const ComparisonOptions& comparison,
                  RelativeMap* map) {
  // Unknown k is member placed[k] (k >= 1); 0 is the basis, held.
  std::vector<int64_t> ids;
  std::vector<Placement*> placed;
  if (!PointPlaced(map, &ids, &placed)) return;
  const int n = static_cast<int>(ids.size());
  // Each member's rotation, and its step from edge 0 to edge 1 when the wall has been seen whole.
  struct Frame {
    Eigen::Matrix2d rot;
    Vector2d step = Vector2d::Zero();
    bool whole = false;
  };
  std::vector<Frame> frames(n);
  for (int k = 0; k < n; ++k) {
    const RltPlane& plane = *in.store.Plane(ids[k]);
    frames[k].rot = Eigen::Rotation2Dd(placed[k]->alpha).toRotationMatrix();
    frames[k].whole = plane.FullLengthKnown();
    if (frames[k].whole) frames[k].step = plane.Length() * frames[k].rot.col(0);
  }
  // What each pairing says: point[to] - point[from] = d.
  struct Link {
    int from, to;
    Vector2d d;
    double w;
  };
  std::vector<Link> links;
  for (int x = 0; x < n; ++x) {
    for (int y = x + 1; y < n; ++y) {
      const Comparison* cmp = in.comparisons.Find(ids[x], ids[y]);
      if (cmp == nullptr) continue;
      // Both directions are the same samples, in either member's frame: half each.
      for (const auto& [u, v] : {std::pair{x, y}, std::pair{y, x}}) {
        const DirectedStats& s = cmp->From(ids[u]);
        const int ru = placed[u]->ref, rv = placed[v]->ref;
        for (int i = 0; i < 2; ++i) {
          if (i != ru && !frames[u].whole) continue;
          for (int j = 0; j < 2; ++j) {
            if (j != rv && !frames[v].whole) continue;
            if (s.pair_count[i][j] <= 0.0) continue;
            const double std_dev = s.PairStd(i, j);
            if (std_dev > comparison.static_std) continue;
            const double spread = std_dev / comparison.spread_scale;
            double w = 0.5 * s.pair_count[i][j] / (1.0 + spread * spread);
            if (i != ru) w *= 0.5;
            if (j != rv) w *= 0.5;
            // From the paired edges to the reference edges.
            const Vector2d d = frames[u].rot * (s.pair_sum[i][j] / s.pair_count[i][j]) +
                               static_cast<double>(i - ru) * frames[u].step -
                               static_cast<double>(j - rv) * frames[v].step;
            links.push_back({u, v, d, w});
          }
        }
      }
    }
  }
  // Only members the links reach from the basis are solved for (the chain's links are among
  // them, so all are, unless a pairing's spread has since passed the bound): the rest keep the
  // chain's placement.
  std::vector<int> index(n, -1);  // unknown's row, -1 when not reached
  index[0] = -2;
  int rows = 0;
  for (bool grew = true; grew;) {
    grew = false;
    for (const Link& l : links) {
      if (index[l.from] != -1 && index[l.to] == -1) index[l.to] = rows++, grew = true;
      if (index[l.to] != -1 && index[l.from] == -1) index[l.from] = rows++, grew = true;
    }
  }
  if (rows == 0) return;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(rows, rows);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(rows, 2);
  for (const Link& l : links) {
    const int f = index[l.from], t = index[l.to];
    if (f == -1 || t == -1) continue;
    // Residual point[to] - point[from] - d; the basis's point is a known term.
    Vector2d known = -l.d;
    if (f == -2) known -= placed[0]->point;
    if (t == -2) known += placed[0]->point;
    if (t >= 0) a(t, t) += l.w, b.row(t) -= l.w * known.transpose();
    if (f >= 0) a(f, f) += l.w, b.row(f) += l.w * known.transpose();
    if (f >= 0 && t >= 0) a(f, t) -= l.w, a(t, f) -= l.w;
  }
  const Eigen::MatrixXd solved = a.ldlt().solve(b);
  if (!solved.allFinite()) return;
  for (int k = 1; k < n; ++k) {
    if (index[k] >= 0) placed[k]->point = solved.row(index[k]).transpose();
  }
}

// §II.D relative map: each point-placed member's line across its wall from the lines of its
// parallel members, where it has them, by least squares with the basis held. A wall end is known
// across its wall to its line's precision but along it only to where the segmenter's last column
// on it fell (a column spacing or more either side of a corner, however often it is seen); a
// pairing through a crossing wall's end carries that end's error along its wall into the
// member's line, whereas two parallel walls' steady lines give their offset to millimetres. So
// RefinePoints' solution stands along each wall and as the lines' prior, at `edge_along_std`;
// each parallel line is weighed as a pairing's samples are (its samples over spread_scale^2,
// half from either member's side). A line steady in each sub-interval at offsets that spread
// over them by more than `static_std` is two surfaces', not taken; lines that disagree with the
// others by more than parallel fits do (`pooled_std`) are not one surface's either: the worst is
// left out and the rest solved again.
void RefineLines(const RelativeMapInputs& in, const ComparisonOptions& comparison,
                 RelativeMap* map) {
  // Unknown k - 1 is member placed[k]'s offset correction along its normal; 0 is the basis.
  std::vector<int64_t> ids;
  std::vector<Placement*> placed;
  if (!PointPlaced(map, &ids, &placed)) return;
  const int n = static_cast<int>(ids.size());
  // A line of v from u's edge: nv . (point[v] + cv nv - point[u] - cu nu) - offset, which is
  // r + cv - c cu with c = nv . nu and r its residual at RefinePoints' placement.
  struct Line {
    int u, v;
    double c, r, w;
  };
  std::vector<Line> lines;
  const double per_sample = 1.0 / (comparison.spread_scale * comparison.spread_scale);
  for (int x = 0; x < n; ++x) {
    for (int y = x + 1; y < n; ++y) {
      const Comparison* cmp = in.comparisons.Find(ids[x], ids[y]);
      if (cmp == nullptr || std::abs(std::sin(cmp->DeltaAlpha(ids[x]))) >= comparison.parallel_sin)
        continue;
      for (const auto& [u, v] : {std::pair{x, y}, std::pair{y, x}}) {
        const DirectedStats& s = cmp->From(ids[u]);
        // v's line from u's edge: the same from either edge of a parallel u.
        for (int i = 0; i < 2; ++i) {
          double offset = 0.0;
          if (!s.Line(i, comparison, &offset)) continue;
          const Vector2d nv = NormalOf(placed[v]->alpha);
          lines.push_back({u, v, nv.dot(NormalOf(placed[u]->alpha)),
                           nv.dot(placed[v]->point - placed[u]->point) - offset,
                           0.5 * s.LineCount(i) * per_sample});
          break;
        }
      }
    }
  }
  const double prior = 1.0 / (comparison.edge_along_std * comparison.edge_along_std);
  std::vector<bool> used(lines.size(), true);
  Eigen::VectorXd dc = Eigen::VectorXd::Zero(n - 1);
  while (true) {  // each round leaves a line out, or ends
    Eigen::MatrixXd a = prior * Eigen::MatrixXd::Identity(n - 1, n - 1);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n - 1);
    for (size_t k = 0; k < lines.size(); ++k) {
      if (!used[k]) continue;
      const Line& l = lines[k];
      const int iu = l.u - 1, iv = l.v - 1;  // -1: the basis, held
      if (iv >= 0) a(iv, iv) += l.w, b(iv) -= l.w * l.r;
      if (iu >= 0) a(iu, iu) += l.w * l.c * l.c, b(iu) += l.w * l.c * l.r;
      if (iu >= 0 && iv >= 0) a(iu, iv) -= l.w * l.c, a(iv, iu) -= l.w * l.c;
    }
    dc = a.ldlt().solve(b);
    if (!dc.allFinite()) return;
    size_t worst = lines.size();
    double worst_residual = comparison.pooled_std;
    for (size_t k = 0; k < lines.size(); ++k) {
      if (!used[k]) continue;
      const Line& l = lines[k];
      const double cu = l.u > 0 ? dc(l.u - 1) : 0.0, cv = l.v > 0 ? dc(l.v - 1) : 0.0;
      const double residual = std::abs(l.r + cv - l.c * cu);
      if (residual > worst_residual) worst = k, worst_residual = residual;
    }
    if (worst == lines.size()) break;
    used[worst] = false;
  }
  for (int k = 1; k < n; ++k) placed[k]->point += dc(k - 1) * NormalOf(placed[k]->alpha);
}

}  // namespace relplane::mapper
