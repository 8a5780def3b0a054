#pragma once
// The sensor's planar path: straight drives between waypoints at constant speed, and turns
// either in place or as arcs that round the corner, both at a constant turn rate. Sampled at
// fixed time steps, so every run sees the same poses.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "relplane/common/geometry.hpp"

namespace relplane::sim {

enum class TurnMode {
  kInPlace,  // stop at each waypoint and rotate on the spot
  kSmooth,   // keep driving through an arc of radius speed / turn_rate (when it fits)
};

struct TrajectoryOptions {
  // Floor-plan points, metres. The drive starts at the first one heading +x (yaw 0).
  std::vector<Eigen::Vector2d> waypoints = {{0.0, 0.0}, {8.0, 0.0}};
  double speed = 1.0;      // m/s along straight parts and arcs
  double turn_rate = 0.8;  // rad/s, never exceeded
  TurnMode turn = TurnMode::kInPlace;
  int laps = 1;             // times round the waypoints; more than one needs closed
  bool closed = false;      // each lap ends back at the first waypoint
  bool drive_back = false;  // after the laps, turn round and retrace the whole path
};

class Trajectory {
 public:
  // Throws std::invalid_argument when the options cannot make a path (fewer than two
  // distinct waypoints, speed or turn rate not positive, laps < 1, laps > 1 without closed).
  explicit Trajectory(const TrajectoryOptions& options);

  double Duration() const { return duration_; }
  // The pose at time t in [0, Duration()] (clamped outside).
  geometry::Pose2 At(double t) const;
  // Samples at t = k * dt for k = 0 .. NumSamples(dt) - 1, the last one at or before the end.
  int64_t NumSamples(double dt) const;
  geometry::Pose2 Sample(int64_t k, double dt) const { return At(static_cast<double>(k) * dt); }

 private:
  enum class Kind { kLine, kArc, kTurn };
  struct Piece {
    Kind kind;
    double start_time;
    double duration;
    Eigen::Vector2d p0;  // line start, arc centre or turn position
    Eigen::Vector2d p1;  // line end
    double yaw0;         // heading at the start
    double sweep;        // signed heading change (arc and turn)
    double radius;       // arc
    double angle0;       // arc: polar angle of the start point about the centre
  };

  void AddLine(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  void AddTurn(const Eigen::Vector2d& at, double yaw0, double sweep);
  void AddArc(const Eigen::Vector2d& centre, double radius, double angle0, double yaw0,
              double sweep);

  TrajectoryOptions options_;
  std::vector<Piece> pieces_;
  double duration_ = 0.0;
};

}  // namespace relplane::sim
