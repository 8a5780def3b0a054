#include "relplane/sim/random_indoor.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace relplane::sim {
namespace {

using Eigen::Vector2d;
using Eigen::Vector2i;

constexpr double kCell = 0.25;  // m: every carved edge lies on this grid

// Free (carved) and solid cells over a box of the floor plan.
class Grid {
 public:
  Grid(const Vector2d& lo, const Vector2d& hi)
      : lo_(lo),
        nx_(static_cast<int>(std::ceil((hi.x() - lo.x()) / kCell))),
        ny_(static_cast<int>(std::ceil((hi.y() - lo.y()) / kCell))),
        free_(static_cast<size_t>(nx_ * ny_), 0) {}

  // Sets every cell inside the box a..b (any corner order) to `value`.
  void Fill(const Vector2d& a, const Vector2d& b, bool value) {
    const Vector2i i0 = Cell(a.cwiseMin(b), 0.5), i1 = Cell(a.cwiseMax(b), -0.5);
    for (int j = std::max(i0.y(), 0); j <= std::min(i1.y(), ny_ - 1); ++j) {
      for (int i = std::max(i0.x(), 0); i <= std::min(i1.x(), nx_ - 1); ++i) {
        free_[static_cast<size_t>(j * nx_ + i)] = value ? 1 : 0;
      }
    }
  }
  bool Free(int i, int j) const {
    return i >= 0 && j >= 0 && i < nx_ && j < ny_ && free_[static_cast<size_t>(j * nx_ + i)] != 0;
  }
  // The boundaries between free and solid cells, merged along each grid line, free space on
  // the left of from -> to.
  std::vector<std::pair<Vector2d, Vector2d>> Walls() const {
    std::vector<std::pair<Vector2d, Vector2d>> out;
    // side: +1 free on the left going +x (free above), -1 free below (the wall runs -x).
    const auto flush = [&out](int side, Vector2d from, Vector2d to) {
      if (side == 0) return;
      if (side < 0) std::swap(from, to);
      out.emplace_back(from, to);
    };
    for (int j = 0; j <= ny_; ++j) {
      int side = 0;
      Vector2d start;
      for (int i = 0; i <= nx_; ++i) {
        const int s = i < nx_ ? (Free(i, j) ? 1 : 0) - (Free(i, j - 1) ? 1 : 0) : 0;
        if (s != side) {
          flush(side, start, Corner(i, j));
          side = s;
          start = Corner(i, j);
        }
      }
    }
    for (int i = 0; i <= nx_; ++i) {
      int side = 0;
      Vector2d start;
      for (int j = 0; j <= ny_; ++j) {
        // Free on +x: the wall runs -y; seen as "side +1" going +y it must be reversed.
        const int s = j < ny_ ? (Free(i - 1, j) ? 1 : 0) - (Free(i, j) ? 1 : 0) : 0;
        if (s != side) {
          flush(side, start, Corner(i, j));
          side = s;
          start = Corner(i, j);
        }
      }
    }
    return out;
  }

 private:
  // The cell holding p nudged by `nudge` cells (so a box's edges on grid lines are exclusive).
  Vector2i Cell(const Vector2d& p, double nudge) const {
    const Vector2d q = (p - lo_) / kCell;
    return {static_cast<int>(std::floor(q.x() + nudge)),
            static_cast<int>(std::floor(q.y() + nudge))};
  }
  Vector2d Corner(int i, int j) const { return lo_ + kCell * Vector2d(i, j); }

  Vector2d lo_;
  int nx_, ny_;
  std::vector<char> free_;
};

struct Room {
  Vector2d centre, half;
};

double Uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
// A multiple of `step` in [lo, hi].
double Quantised(std::mt19937_64& rng, double lo, double hi, double step) {
  const int n0 = static_cast<int>(std::ceil(lo / step - 1e-9));
  const int n1 = static_cast<int>(std::floor(hi / step + 1e-9));
  return step * std::uniform_int_distribution<int>(n0, std::max(n0, n1))(rng);
}
bool Chance(std::mt19937_64& rng, double p) { return Uniform(rng, 0.0, 1.0) < p; }

double DistanceToSegment(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// The sites of the rooms on a lattice: a loop round a 2 x 2 or 2 x 3 block, or an open walk
// of 3-5 sites that never visits a site twice.
std::vector<Vector2i> Sites(std::mt19937_64& rng, bool loop) {
  if (loop) {
    if (Chance(rng, 0.5)) return {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    if (Chance(rng, 0.5)) return {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}};
    return {{0, 0}, {1, 0}, {1, 1}, {1, 2}, {0, 2}, {0, 1}};
  }
  const int n = std::uniform_int_distribution<int>(3, 5)(rng);
  for (;;) {
    std::vector<Vector2i> sites = {{0, 0}};
    while (static_cast<int>(sites.size()) < n) {
      std::vector<Vector2i> next;
      for (const Vector2i& d : {Vector2i(1, 0), Vector2i(-1, 0), Vector2i(0, 1), Vector2i(0, -1)}) {
        const Vector2i s = sites.back() + d;
        if (std::find(sites.begin(), sites.end(), s) == sites.end()) next.push_back(s);
      }
      if (next.empty()) break;
      sites.push_back(next[std::uniform_int_distribution<size_t>(0, next.size() - 1)(rng)]);
    }
    if (static_cast<int>(sites.size()) == n) return sites;
  }
}

}  // namespace

IndoorLayout MakeRandomIndoor(const RandomIndoorParams& params) {
  std::mt19937_64 rng(params.seed * 0x9E3779B97F4A7C15ULL + 0x5EED);
  IndoorLayout out;
  out.closed = Chance(rng, 0.5);
  out.drive_back = !out.closed;
  const std::vector<Vector2i> sites = Sites(rng, out.closed);
  // Twice round the small loops only, so a run stays within two minutes or so.
  out.laps = out.closed && sites.size() == 4 && Chance(rng, 0.5) ? 2 : 1;
  const double spacing = Quantised(rng, 8.0, 12.0, 1.0);  // m between room centres

  std::vector<Room> rooms;
  Vector2d lo = Vector2d::Constant(1e9), hi = Vector2d::Constant(-1e9);
  for (const Vector2i& s : sites) {
    const double max_side = std::min(7.0, spacing - 3.0);
    const Room r{spacing * s.cast<double>(), 0.5 * Vector2d(Quantised(rng, 3.0, max_side, 0.5),
                                                            Quantised(rng, 3.0, max_side, 0.5))};
    rooms.push_back(r);
    lo = lo.cwiseMin(r.centre - r.half);
    hi = hi.cwiseMax(r.centre + r.half);
  }
  Grid grid(lo - Vector2d::Constant(2.0), hi + Vector2d::Constant(2.0));
  for (const Room& r : rooms) grid.Fill(r.centre - r.half, r.centre + r.half, true);

  // Corridors between consecutive rooms (and back to the first on a loop): straight, since the
  // rooms' centres share a lattice row or column.
  int corridors = 0, recesses = 0, doorways = 0, pillars = 0;
  struct Leg {
    size_t a, b;
    double half_width;
  };
  std::vector<Leg> legs;
  for (size_t k = 0; k + 1 < rooms.size() + (out.closed ? 1 : 0); ++k) {
    legs.push_back({k, (k + 1) % rooms.size(), 0.5 * Quantised(rng, 1.5, 2.5, 0.5)});
  }
  for (const Leg& leg : legs) {
    const Room& a = rooms[leg.a];
    const Room& b = rooms[leg.b];
    const Vector2d t = (b.centre - a.centre).normalized();
    const Vector2d n(-t.y(), t.x());
    grid.Fill(a.centre - leg.half_width * n, b.centre + leg.half_width * n, true);
    ++corridors;
    // Where the corridor leaves each room: the room's edge along t.
    const double a_edge = std::abs(a.half.dot(t)), b_edge = std::abs(b.half.dot(t));
    const double length = (b.centre - a.centre).norm();
    // Door recesses in either wall of the corridor, half a metre clear of the rooms.
    for (const double side : {-1.0, 1.0}) {
      if (!Chance(rng, 0.4)) continue;
      const double every = Quantised(rng, 2.0, 3.5, 0.25);
      const double depth = Quantised(rng, 0.25, 0.5, 0.25);
      for (double s = a_edge + 0.5; s + 1.0 <= length - b_edge - 0.5; s += every) {
        const Vector2d p0 = a.centre + s * t + side * leg.half_width * n;
        grid.Fill(p0, p0 + 1.0 * t + side * depth * n, true);
        ++recesses;
      }
    }
    // Doorways: a jamb wall one cell thick across the corridor at a room's edge, with an
    // opening wide enough to keep the route clear.
    for (const auto& [room, sign, edge] :
         {std::tuple{&a, 1.0, a_edge}, std::tuple{&b, -1.0, b_edge}}) {
      // Half a metre steps keep the jambs' edges on the grid.
      const double door =
          Quantised(rng, 2.0 * kRouteClearance + 0.05, 2.0 * leg.half_width - 0.5, 0.5);
      if (door >= 2.0 * leg.half_width || !Chance(rng, 0.5)) continue;
      const Vector2d at = room->centre + sign * edge * t;
      const Vector2d deep = sign * kCell * t;
      grid.Fill(at + 0.5 * door * n, at + deep + leg.half_width * n, false);
      grid.Fill(at - 0.5 * door * n, at + deep - leg.half_width * n, false);
      ++doorways;
    }
  }
  // The route: the rooms' centres in order.
  for (const Room& r : rooms) out.route.push_back(r.centre);
  const auto route_distance = [&](const Vector2d& p) {
    double d = 1e9;
    for (size_t k = 0; k + 1 < out.route.size() + (out.closed ? 1 : 0); ++k) {
      d = std::min(d, DistanceToSegment(p, out.route[k], out.route[(k + 1) % out.route.size()]));
    }
    return d;
  };
  // Pillars at the quarter points of large rooms, clear of the route.
  for (const Room& r : rooms) {
    if (r.half.minCoeff() < 2.25) continue;
    for (const Vector2d& q : {Vector2d(1, 1), Vector2d(1, -1), Vector2d(-1, 1), Vector2d(-1, -1)}) {
      const double side = Chance(rng, 0.5) ? 0.5 : 0.25;
      const Vector2d c = r.centre + 0.5 * r.half.cwiseProduct(q);
      // A corner on the grid, so the pillar is whole cells.
      const Vector2d corner =
          ((c - Vector2d::Constant(0.5 * side)) / kCell).array().round().matrix() * kCell;
      const Vector2d centre = corner + Vector2d::Constant(0.5 * side);
      if (!Chance(rng, 0.6) || route_distance(centre) < kRouteClearance + side) continue;
      grid.Fill(corner, corner + Vector2d::Constant(side), false);
      ++pillars;
    }
  }
  out.walls = grid.Walls();
  out.description = std::to_string(rooms.size()) + " rooms " +
                    std::to_string(static_cast<int>(spacing)) + " m apart, " +
                    std::to_string(corridors) + " corridors, " + std::to_string(pillars) +
                    " pillars, " + std::to_string(doorways) + " doorways, " +
                    std::to_string(recesses) + " recesses; route: " +
                    (out.closed ? (out.laps == 2 ? "a loop driven twice" : "a loop")
                                : "out to the last room and back");
  return out;
}

}  // namespace relplane::sim
