#include "relplane/eval/map_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace relplane::eval {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;
constexpr double kWallNormalZMax = 0.1;

// Interval of `s` along the unit direction `dir` (from the origin).
std::pair<double, double> Extent(const geometry::Segment2& s, const Eigen::Vector2d& dir) {
  const double ta = dir.dot(s.a);
  const double tb = dir.dot(s.b);
  return {std::min(ta, tb), std::max(ta, tb)};
}

struct Candidate {
  bool ok = false;
  double angle_deg = 0.0;
  double offset_m = 0.0;
  double overlap_m = 0.0;
};

Candidate Compare(const WallLine& truth, const WallLine& mapped, const MatchOptions& options) {
  Candidate c;
  const double cosine = std::min(1.0, std::abs(truth.normal.dot(mapped.normal)));
  c.angle_deg = std::acos(cosine) * kRadToDeg;
  c.offset_m = std::abs(truth.normal.dot(mapped.segment.Midpoint()) + truth.offset);
  const Eigen::Vector2d dir(-truth.normal.y(), truth.normal.x());
  const auto [t0, t1] = Extent(truth.segment, dir);
  const auto [m0, m1] = Extent(mapped.segment, dir);
  c.overlap_m = std::min(t1, m1) - std::max(t0, m0);
  // A short mapped piece (a wall seen end-on) needs only half its length inside the true wall.
  const double needed = std::min(options.overlap_min_m, 0.5 * (m1 - m0));
  c.ok = c.angle_deg < options.angle_max_deg && c.offset_m < options.offset_max_m &&
         c.overlap_m >= needed && c.overlap_m > 0.0;
  return c;
}

// Segment ends ordered along `dir`.
std::pair<Eigen::Vector2d, Eigen::Vector2d> OrderedEnds(const geometry::Segment2& s,
                                                        const Eigen::Vector2d& dir) {
  if (dir.dot(s.a) <= dir.dot(s.b)) return {s.a, s.b};
  return {s.b, s.a};
}

// True when segments p->q and a->b cross strictly inside p->q.
bool Blocks(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const geometry::Segment2& wall) {
  const Eigen::Vector2d r = q - p;
  const Eigen::Vector2d s = wall.b - wall.a;
  const double denom = r.x() * s.y() - r.y() * s.x();
  if (std::abs(denom) < 1e-12) return false;
  const Eigen::Vector2d w = wall.a - p;
  const double u = (w.x() * s.y() - w.y() * s.x()) / denom;  // along the line of sight
  const double v = (w.x() * r.y() - w.y() * r.x()) / denom;  // along the wall
  return u > 1e-6 && u < 1.0 - 1e-6 && v >= 0.0 && v <= 1.0;
}

void Summarise(const std::vector<double>& values, ErrorSummary* out) {
  if (values.empty()) return;
  double sum = 0.0;
  out->max = 0.0;
  for (const double v : values) {
    sum += v;
    out->max = std::max(out->max, v);
  }
  out->mean = sum / static_cast<double>(values.size());
}

// Truth poses thinned to those that moved or turned noticeably: visibility is tested per pose.
std::vector<PoseSample> Thinned(const std::vector<PoseSample>& poses) {
  std::vector<PoseSample> kept;
  for (const PoseSample& p : poses) {
    if (!kept.empty()) {
      const PoseSample& last = kept.back();
      const double moved = (p.position.head<2>() - last.position.head<2>()).norm();
      const double turned = std::abs(
          geometry::WrapAngle(geometry::YawOf(p.orientation) - geometry::YawOf(last.orientation)));
      if (moved < 0.1 && turned < 5.0 * M_PI / 180.0) continue;
    }
    kept.push_back(p);
  }
  return kept;
}

const WallLine& ById(const std::vector<WallLine>& walls, int64_t id) {
  return *std::find_if(walls.begin(), walls.end(), [&](const WallLine& w) { return w.id == id; });
}

// The matches of one true wall beyond its best: a plane covering part of the wall that a better
// match facing the same way already covers maps that part twice (a duplicate); one covering
// only what better matches facing the other way cover is the wall's other face (a partition
// seen from both rooms: the world's walls have no thickness, its faces two surfaces); one
// covering only what no better match covers is the wall mapped in pieces (a fragment: an outer
// wall seen from each room between the partitions that meet it, where the sensor never sees that
// the pieces are one).
void CountExtraMatches(const WallLine& truth,
                       const std::vector<std::pair<Candidate, int64_t>>& best_first,
                       const std::vector<WallLine>& mapped, const MatchOptions& options,
                       MapMetrics* m) {
  const Eigen::Vector2d dir = truth.segment.Direction();
  for (size_t k = 1; k < best_first.size(); ++k) {
    const WallLine& a = ById(mapped, best_first[k].second);
    const auto [a0, a1] = Extent(a.segment, dir);
    const double needed = std::min(options.overlap_min_m, 0.5 * (a1 - a0));
    bool covered = false, other_face = false;
    for (size_t j = 0; j < k && !covered; ++j) {
      const WallLine& b = ById(mapped, best_first[j].second);
      const auto [b0, b1] = Extent(b.segment, dir);
      if (std::min(a1, b1) - std::max(a0, b0) < needed) continue;
      (a.normal.dot(b.normal) > 0.0 ? covered : other_face) = true;
    }
    ++(covered ? m->duplicates : other_face ? m->other_faces : m->fragments);
  }
}

// Distances along `wall` from its first end of the points tested for visibility.
std::vector<double> WallSamples(const WallLine& wall, const VisibilityOptions& options) {
  const double length = wall.segment.Length();
  // Stay a little inside the ends so a wall meeting this one at a corner does not hide it.
  const double inset = std::min(0.05, 0.25 * length);
  const int steps = std::max(
      1, static_cast<int>(std::ceil((length - 2 * inset) / std::max(options.sample_step_m, 0.01))));
  std::vector<double> along;
  for (int k = 0; k <= steps; ++k) along.push_back(inset + (length - 2 * inset) * k / steps);
  return along;
}

// Whether `q`, on `wall`, is in range and field of view of some pose with no other wall of
// `walls` crossing the line of sight.
bool PointSeenFrom(const Eigen::Vector2d& q, const WallLine& wall,
                   const std::vector<WallLine>& walls, const std::vector<PoseSample>& poses,
                   const VisibilityOptions& options) {
  const double half_fov = 0.5 * options.hfov_deg * M_PI / 180.0;
  for (const PoseSample& pose : poses) {
    const Eigen::Vector2d p = pose.position.head<2>();
    const Eigen::Vector2d ray = q - p;
    if (ray.norm() > options.range_m) continue;
    const double yaw = geometry::YawOf(pose.orientation);
    if (std::abs(geometry::WrapAngle(std::atan2(ray.y(), ray.x()) - yaw)) > half_fov) continue;
    const bool blocked = std::any_of(walls.begin(), walls.end(), [&](const WallLine& other) {
      return other.id != wall.id && Blocks(p, q, other.segment);
    });
    if (!blocked) return true;
  }
  return false;
}

// What the truth trajectory saw of a true wall: its samples along the wall (from its lower
// end along Direction()) and which were seen.
struct WallView {
  Eigen::Vector2d lo, hi;  // the wall's ends in the order of its direction
  std::vector<double> along;
  std::vector<bool> seen;
  bool seen_any = false;
  bool end_seen[2] = {false, false};
  double visible_length_m = 0.0;
};

WallView ViewOf(const WallLine& wall, const std::vector<WallLine>& occluders,
                const std::vector<PoseSample>& viewpoints, const VisibilityOptions& options) {
  WallView view;
  const Eigen::Vector2d dir = wall.segment.Direction();
  view.lo = wall.segment.a;
  view.hi = wall.segment.b;
  view.along = WallSamples(wall, options);
  for (const double t : view.along) {
    view.seen.push_back(
        PointSeenFrom(wall.segment.a + t * dir, wall, occluders, viewpoints, options));
  }
  const size_t n = view.seen.size();
  view.seen_any = std::find(view.seen.begin(), view.seen.end(), true) != view.seen.end();
  view.end_seen[0] = view.seen.front();
  view.end_seen[1] = view.seen.back();
  // Each sample stands for the wall up to half way to its neighbours (the ends included).
  const double length = wall.segment.Length();
  for (size_t k = 0; k < n; ++k) {
    if (!view.seen[k]) continue;
    const double from = k == 0 ? 0.0 : 0.5 * (view.along[k - 1] + view.along[k]);
    const double to = k + 1 == n ? length : 0.5 * (view.along[k] + view.along[k + 1]);
    view.visible_length_m += to - from;
  }
  return view;
}

struct Coverage {
  double mapped_length_m = 0.0;  // of the wall, under the union of its matches
  double fraction = 0.0;         // of the visible part (of the whole wall when none seen)
  Eigen::Vector2d ends[2];       // the matches' outermost ends, in the wall's direction
};

// How much of a true wall its matches cover, all fragments together (§ docs/run-folder.md).
Coverage CoverageOf(const WallLine& wall, const std::vector<std::pair<Candidate, int64_t>>& list,
                    const std::vector<WallLine>& mapped, const WallView& view) {
  Coverage c;
  if (list.empty()) return c;
  const Eigen::Vector2d dir = wall.segment.Direction();
  const double base = dir.dot(wall.segment.a);
  const double length = wall.segment.Length();
  std::vector<std::pair<double, double>> spans;  // along the wall, from its first end
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (const auto& match : list) {
    const WallLine& w = ById(mapped, match.second);
    const auto [m0, m1] = Extent(w.segment, dir);
    spans.push_back({std::max(0.0, m0 - base), std::min(length, m1 - base)});
    const auto [e0, e1] = OrderedEnds(w.segment, dir);
    if (m0 < lo) lo = m0, c.ends[0] = e0;
    if (m1 > hi) hi = m1, c.ends[1] = e1;
  }
  std::sort(spans.begin(), spans.end());
  double reach = 0.0;
  for (const auto& [from, to] : spans) {
    const double start = std::max(from, reach);
    if (to > start) c.mapped_length_m += to - start;
    reach = std::max(reach, to);
  }
  const auto covered = [&](double t) {
    return std::any_of(spans.begin(), spans.end(),
                       [&](const auto& span) { return span.first <= t && t <= span.second; });
  };
  if (!view.seen_any) {
    c.fraction = length > 0.0 ? c.mapped_length_m / length : 0.0;
    return c;
  }
  size_t seen = 0, seen_covered = 0;
  for (size_t k = 0; k < view.along.size(); ++k) {
    if (!view.seen[k]) continue;
    ++seen;
    if (covered(view.along[k])) ++seen_covered;
  }
  c.fraction = static_cast<double>(seen_covered) / static_cast<double>(seen);
  return c;
}

}  // namespace

std::vector<WallLine> WallsOf(const std::vector<PlaneRecord>& planes, int64_t* without_extent) {
  std::vector<WallLine> walls;
  for (const PlaneRecord& plane : planes) {
    const Eigen::Vector2d n2 = plane.normal.head<2>();
    if (std::abs(plane.normal.z()) >= kWallNormalZMax || n2.norm() < 1e-9) continue;
    WallLine wall;
    wall.id = plane.id;
    wall.normal = n2.normalized();
    const Eigen::Vector2d dir(-wall.normal.y(), wall.normal.x());
    double t_min = 0.0;
    double t_max = 0.0;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (size_t i = 0; i < plane.vertices.size(); ++i) {
      const Eigen::Vector3d& v = plane.vertices[i];
      const double t = dir.dot(v.head<2>());
      t_min = i == 0 ? t : std::min(t_min, t);
      t_max = i == 0 ? t : std::max(t_max, t);
      wall.z_min = i == 0 ? v.z() : std::min(wall.z_min, v.z());
      wall.z_max = i == 0 ? v.z() : std::max(wall.z_max, v.z());
      mean += v.head<2>();
    }
    if (plane.vertices.size() < 2 || t_max - t_min < 1e-6) {
      if (without_extent != nullptr) ++*without_extent;
      continue;
    }
    mean /= static_cast<double>(plane.vertices.size());
    wall.offset = -wall.normal.dot(mean);
    const Eigen::Vector2d foot = -wall.offset * wall.normal;  // the line's point nearest 0
    wall.segment.a = foot + t_min * dir;
    wall.segment.b = foot + t_max * dir;
    walls.push_back(wall);
  }
  return walls;
}

double SensorHeight(const std::vector<PoseSample>& truth) {
  if (truth.empty()) return kNaN;
  std::vector<double> z;
  z.reserve(truth.size());
  for (const PoseSample& p : truth) z.push_back(p.position.z());
  std::nth_element(z.begin(), z.begin() + z.size() / 2, z.end());
  return z[z.size() / 2];
}

bool SpansHeight(const WallLine& wall, double z) {
  return std::isnan(z) || (wall.z_min <= z && z <= wall.z_max);
}

bool WallSeenFrom(const WallLine& wall, const std::vector<WallLine>& walls,
                  const std::vector<PoseSample>& poses, const VisibilityOptions& options) {
  const Eigen::Vector2d dir = wall.segment.Direction();
  for (const double t : WallSamples(wall, options)) {
    if (PointSeenFrom(wall.segment.a + t * dir, wall, walls, poses, options)) return true;
  }
  return false;
}

MapMetrics ComputeMapMetrics(const MapSnapshot& world, const MapSnapshot& map,
                             const std::vector<PoseSample>& truth, const EvalOptions& options) {
  MapMetrics m;
  m.has_truth = !world.planes.empty();
  m.mapped_planes = static_cast<int64_t>(map.planes.size());
  // Only walls at the sensor's height are walls to a 2½D sensor, for counting and occluding.
  const double sensor_z = SensorHeight(truth);
  std::vector<WallLine> occluders;
  std::vector<WallLine> true_walls;
  std::vector<WallLine> short_walls;  // door jambs and the like: too short to be scored
  for (const WallLine& w : WallsOf(world.planes)) {
    if (!SpansHeight(w, sensor_z)) continue;
    occluders.push_back(w);
    if (w.segment.Length() >= options.visibility.min_wall_length_m) {
      true_walls.push_back(w);
    } else {
      short_walls.push_back(w);
    }
  }
  const std::vector<WallLine> mapped = WallsOf(map.planes, &m.mapped_without_extent);
  m.true_walls = static_cast<int64_t>(true_walls.size());
  m.mapped_walls = static_cast<int64_t>(mapped.size());

  // Each mapped wall goes to the nearest line among the true walls lying along most of it, and
  // to the true wall it overlaps most when none does. Overlap alone gave a pilaster's 0.4 m
  // face, mapped 2 cm off, to the wall 0.3 m behind it, which it overlapped 1 cm longer; a long
  // wall passing a pilaster still goes to the wall, as the face lies along little of it.
  std::vector<std::vector<std::pair<Candidate, int64_t>>> matches(true_walls.size());
  for (const WallLine& w : mapped) {
    const double along_most = 0.5 * w.segment.Length();
    // The best of `walls` for w: -1 if none compares.
    auto best_of = [&](const std::vector<WallLine>& walls, Candidate* best_c, bool* best_along) {
      int best = -1;
      for (size_t t = 0; t < walls.size(); ++t) {
        const Candidate c = Compare(walls[t], w, options.match);
        if (!c.ok) continue;
        const bool along = c.overlap_m >= along_most;
        const bool better =
            best < 0 || (along && !*best_along) ||
            (along == *best_along &&
             (along ? c.offset_m < best_c->offset_m
                    : c.overlap_m > best_c->overlap_m ||
                          (c.overlap_m == best_c->overlap_m && c.offset_m < best_c->offset_m)));
        if (better) {
          best = static_cast<int>(t);
          *best_c = c;
          *best_along = along;
        }
      }
      return best;
    };
    Candidate best_c, short_c;
    bool best_along = false, short_along = false;
    const int best = best_of(true_walls, &best_c, &best_along);
    const int on_short = best_of(short_walls, &short_c, &short_along);
    // The short surfaces (a partition's end face, a jamb) take part in the same rule: one mapped
    // on its surface is that surface, not a second version of a scored wall further off that it
    // also lies along (as a pilaster's face above), and it is not scored.
    const bool short_is_nearer =
        on_short >= 0 && short_along && (!best_along || short_c.offset_m < best_c.offset_m);
    if (best < 0 || short_is_nearer) {
      // A mapped jamb where a jamb is is not spurious, only not scored.
      if (on_short >= 0) {
        ++m.on_short_walls;
      } else if (m.has_truth) {
        m.spurious_ids.push_back(w.id);
      }
    } else {
      matches[best].push_back({best_c, w.id});
    }
  }
  m.spurious = static_cast<int64_t>(m.spurious_ids.size());
  const std::vector<PoseSample> viewpoints = Thinned(truth);

  std::vector<double> normal_errors, offset_errors, endpoint_errors;
  for (size_t t = 0; t < true_walls.size(); ++t) {
    const WallLine& tw = true_walls[t];
    WallMatch wm;
    wm.true_id = tw.id;
    wm.length_m = tw.segment.Length();
    auto& list = matches[t];
    std::stable_sort(list.begin(), list.end(), [](const auto& x, const auto& y) {
      return x.first.overlap_m > y.first.overlap_m;
    });
    for (const auto& [c, id] : list) wm.mapped_ids.push_back(id);
    const WallView view = ViewOf(tw, occluders, viewpoints, options.visibility);
    const Coverage cover = CoverageOf(tw, list, mapped, view);
    wm.visible_length_m = view.visible_length_m;
    wm.mapped_length_m = cover.mapped_length_m;
    wm.coverage = cover.fraction;
    wm.mapped = cover.fraction >= kMappedCoverageMin;
    if (!list.empty()) {
      const Candidate& c = list.front().first;
      wm.normal_error_deg = c.angle_deg;
      wm.offset_error_m = c.offset_m;
      wm.overlap_m = c.overlap_m;
      normal_errors.push_back(wm.normal_error_deg);
      offset_errors.push_back(wm.offset_error_m);
      // Each end seen against the fragments' outermost ends.
      for (int end = 0; end < 2; ++end) {
        if (!view.end_seen[end] && view.seen_any) continue;
        wm.endpoint_error_m[end] = (cover.ends[end] - (end == 0 ? view.lo : view.hi)).norm();
        endpoint_errors.push_back(wm.endpoint_error_m[end]);
      }
      CountExtraMatches(tw, list, mapped, options.match, &m);
    }
    if (wm.mapped) ++m.walls_mapped;
    if (!list.empty() && !wm.mapped) ++m.partly_mapped;
    wm.expected = !list.empty() || view.seen_any;
    if (wm.expected) ++m.expected_walls;
    if (wm.expected && !wm.mapped) ++m.missed;
    m.walls.push_back(wm);
  }
  Summarise(normal_errors, &m.normal_error_deg);
  Summarise(offset_errors, &m.offset_error_m);
  Summarise(endpoint_errors, &m.endpoint_error_m);
  return m;
}

}  // namespace relplane::eval
