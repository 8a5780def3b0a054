#include "relplane/sim/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace relplane::sim {

namespace {

using Eigen::Vector2d;

double Heading(const Vector2d& v) { return std::atan2(v.y(), v.x()); }

// The polyline the robot follows: laps round the waypoints, then the way back if asked,
// without repeated points.
std::vector<Vector2d> Polyline(const TrajectoryOptions& o) {
  std::vector<Vector2d> path;
  for (int lap = 0; lap < o.laps; ++lap) {
    for (size_t i = 0; i < o.waypoints.size(); ++i) {
      if (lap > 0 && i == 0) continue;  // the previous lap ended here
      path.push_back(o.waypoints[i]);
    }
    if (o.closed) path.push_back(o.waypoints.front());
  }
  if (o.drive_back) {
    const std::vector<Vector2d> forward = path;
    for (auto it = forward.rbegin() + 1; it != forward.rend(); ++it) path.push_back(*it);
  }
  std::vector<Vector2d> unique;
  for (const Vector2d& p : path) {
    if (unique.empty() || (p - unique.back()).norm() > 1e-9) unique.push_back(p);
  }
  return unique;
}

}  // namespace

Trajectory::Trajectory(const TrajectoryOptions& options) : options_(options) {
  if (!(options.speed > 0.0)) throw std::invalid_argument("speed must be positive");
  if (!(options.turn_rate > 0.0)) throw std::invalid_argument("turn_rate must be positive");
  if (options.laps < 1) throw std::invalid_argument("laps must be at least 1");
  if (options.laps > 1 && !options.closed) {
    throw std::invalid_argument("laps > 1 needs closed: true");
  }
  const std::vector<Vector2d> path = Polyline(options);
  if (path.size() < 2) throw std::invalid_argument("needs at least two distinct waypoints");

  const size_t n = path.size();
  std::vector<Vector2d> dir(n - 1);
  std::vector<double> length(n - 1);
  for (size_t i = 0; i + 1 < n; ++i) {
    length[i] = (path[i + 1] - path[i]).norm();
    dir[i] = (path[i + 1] - path[i]) / length[i];
  }
  // At each inner vertex: the signed turn and, for an arc, how much of each adjacent
  // segment it replaces. An arc must fit in half of each segment and cannot reverse
  // direction; otherwise the robot turns in place.
  const double radius = options.speed / options.turn_rate;
  std::vector<double> turn(n, 0.0);
  std::vector<double> cut(n, 0.0);
  for (size_t i = 1; i + 1 < n; ++i) {
    turn[i] = geometry::WrapAngle(Heading(dir[i]) - Heading(dir[i - 1]));
    if (options.turn != TurnMode::kSmooth) continue;
    const double tangent = radius * std::tan(0.5 * std::abs(turn[i]));
    if (std::abs(turn[i]) < 3.0 && tangent <= 0.5 * length[i - 1] && tangent <= 0.5 * length[i]) {
      cut[i] = tangent;
    }
  }

  // The start pose faces +x; turn towards the first segment first if needed.
  const double first = Heading(dir[0]);
  if (std::abs(geometry::WrapAngle(first)) > 1e-12) {
    AddTurn(path[0], 0.0, geometry::WrapAngle(first));
  }
  for (size_t i = 0; i + 1 < n; ++i) {
    const Vector2d a = path[i] + cut[i] * dir[i];
    const Vector2d b = path[i + 1] - cut[i + 1] * dir[i];
    AddLine(a, b);
    const size_t v = i + 1;
    if (v + 1 >= n || std::abs(turn[v]) < 1e-12) continue;
    const double yaw = Heading(dir[i]);
    if (cut[v] > 0.0) {
      // The arc's centre lies on the inside of the turn, one radius from the line.
      const double side = turn[v] > 0.0 ? 1.0 : -1.0;
      const Vector2d normal(-dir[i].y(), dir[i].x());
      const Vector2d centre = b + side * radius * normal;
      AddArc(centre, radius, Heading(b - centre), yaw, turn[v]);
    } else {
      AddTurn(path[v], yaw, turn[v]);
    }
  }
}

void Trajectory::AddLine(const Vector2d& a, const Vector2d& b) {
  const double length = (b - a).norm();
  if (length <= 0.0) return;
  Piece p{Kind::kLine, duration_, length / options_.speed, a, b, Heading(b - a), 0.0, 0.0, 0.0};
  pieces_.push_back(p);
  duration_ += p.duration;
}

void Trajectory::AddTurn(const Vector2d& at, double yaw0, double sweep) {
  Piece p{Kind::kTurn, duration_, std::abs(sweep) / options_.turn_rate, at, at, yaw0, sweep,
          0.0,         0.0};
  pieces_.push_back(p);
  duration_ += p.duration;
}

void Trajectory::AddArc(const Vector2d& centre, double radius, double angle0, double yaw0,
                        double sweep) {
  Piece p{Kind::kArc, duration_, radius * std::abs(sweep) / options_.speed,
          centre,     centre,    yaw0,
          sweep,      radius,    angle0};
  pieces_.push_back(p);
  duration_ += p.duration;
}

geometry::Pose2 Trajectory::At(double t) const {
  t = std::clamp(t, 0.0, duration_);
  // The last piece starting at or before t.
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), t,
                             [](double time, const Piece& p) { return time < p.start_time; });
  const Piece& p = *(it == pieces_.begin() ? it : it - 1);
  const double f = p.duration > 0.0 ? std::clamp((t - p.start_time) / p.duration, 0.0, 1.0) : 1.0;
  geometry::Pose2 pose;
  switch (p.kind) {
    case Kind::kLine: {
      const Vector2d q = p.p0 + f * (p.p1 - p.p0);
      pose = {q.x(), q.y(), p.yaw0};
      break;
    }
    case Kind::kTurn:
      pose = {p.p0.x(), p.p0.y(), p.yaw0 + f * p.sweep};
      break;
    case Kind::kArc: {
      const double angle = p.angle0 + f * p.sweep;
      pose = {p.p0.x() + p.radius * std::cos(angle), p.p0.y() + p.radius * std::sin(angle),
              p.yaw0 + f * p.sweep};
      break;
    }
  }
  pose.yaw = geometry::WrapAngle(pose.yaw);
  return pose;
}

int64_t Trajectory::NumSamples(double dt) const {
  return static_cast<int64_t>(std::floor(duration_ / dt + 1e-9)) + 1;
}

}  // namespace relplane::sim
