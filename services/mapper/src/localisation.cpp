#include "relplane/mapper/localisation.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <set>

#include "relplane/mapper/relative_map.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

constexpr double kOutlier = 0.3;      // m: a wall this far from its line is left out
constexpr double kEdgeGate = 0.1;     // m: motion model snaps to a mapped end this close

struct System {
  Matrix2d a = Matrix2d::Zero();
  Vector2d b = Vector2d::Zero();
  void Add(const Vector2d& dir, double value) {
    a += dir * dir.transpose();
    b += dir * value;
  }
};

}  // namespace

PoseEstimate Localise(const std::vector<Sighting>& sightings, const geometry::Pose2& previous,
                      const LearnedFrustum& frustum, const LocalisationOptions& options) {
  PoseEstimate out;
  out.pose = previous;
  std::vector<bool> use(sightings.size(), true);
  for (int round = 0; round < 2; ++round) {
    double s = 0.0, c = 0.0;
    int n = 0;
    for (size_t k = 0; k < sightings.size(); ++k) {
      if (!use[k]) continue;
      const double d = sightings[k].world.alpha - sightings[k].obs->Alpha();
      s += std::sin(d), c += std::cos(d), ++n;
    }
    if (n == 0) {
      out.status = PoseStatus::kLost;
      out.planes = 0;
      return out;
    }
    const double yaw = std::atan2(s, c);
    const Matrix2d rot = Eigen::Rotation2Dd(yaw).toRotationMatrix();
    System sys;
    std::set<int64_t> planes;
    for (size_t k = 0; k < sightings.size(); ++k) {
      if (!use[k]) continue;
      const Sighting& x = sightings[k];
      if (x.world.known == Known::kAngle) continue;
      planes.insert(x.plane->Id());
      // The sensor is d in front of the wall's line: n . c = n . P + d.
      const Vector2d n = NormalOf(x.world.alpha);
      sys.Add(n, n.dot(x.world.point) + x.obs->d);
    }
    // A static edge seen now fixes the position along the wall (c + R e = P); used only where
    // the lines leave a direction open, as an edge taken for static may drift (occlusion).
    Eigen::SelfAdjointEigenSolver<Matrix2d> line_eig(sys.a);
    for (size_t k = 0; k < sightings.size(); ++k) {
      if (line_eig.eigenvalues()(0) >= options.min_information) break;
      const Sighting& x = sightings[k];
      if (!use[k] || x.world.known == Known::kAngle) continue;
      const Vector2d t = DirectionOf(x.world.alpha);
      for (int e = 0; e < 2; ++e) {
        Vector2d mapped;
        if (!x.plane->static_now[e] || x.plane->static_now_iteration != x.obs->iteration) continue;
        if (frustum.Clipped(x.obs->edge[e])) continue;
        if (!EdgePoint(*x.plane, x.world, e, &mapped)) continue;
        sys.Add(t, t.dot(mapped - rot * x.obs->edge[e]));
      }
    }
    Eigen::SelfAdjointEigenSolver<Matrix2d> eig(sys.a);
    const double information = eig.eigenvalues()(0);
    const bool tracking = planes.size() >= 2 && information >= options.min_information;
    if (!tracking) {
      // §II.E motion model: a mapped wall end seen where the previous position predicts it.
      for (size_t k = 0; k < sightings.size(); ++k) {
        const Sighting& x = sightings[k];
        if (!use[k] || x.world.known != Known::kPoint) continue;
        const Vector2d t = DirectionOf(x.world.alpha);
        for (int e = 0; e < 2; ++e) {
          Vector2d mapped;
          if (frustum.Clipped(x.obs->edge[e])) continue;  // cut by the view, not a wall end
          if (!EdgePoint(*x.plane, x.world, e, &mapped)) continue;
          const double along = t.dot(mapped - rot * x.obs->edge[e]);
          if (std::abs(along - t.dot(previous.Translation())) < kEdgeGate) sys.Add(t, along);
        }
      }
    }
    // The previous position only decides a direction the walls leave open.
    Eigen::SelfAdjointEigenSolver<Matrix2d> final_eig(sys.a);
    if (final_eig.eigenvalues()(0) < options.min_information) {
      sys.a += options.prior_weight * Matrix2d::Identity();
      sys.b += options.prior_weight * previous.Translation();
    }
    const Vector2d pos = sys.a.ldlt().solve(sys.b);
    out.pose = {pos.x(), pos.y(), yaw};
    out.planes = static_cast<int>(planes.size());
    out.status = tracking ? PoseStatus::kTracking : PoseStatus::kMotionModel;
    // One round of outlier rejection: a mis-registered wall must not drag the pose.
    bool dropped = false;
    for (size_t k = 0; k < sightings.size() && round == 0; ++k) {
      const Sighting& x = sightings[k];
      if (!use[k] || x.world.known == Known::kAngle || sightings.size() < 3) continue;
      const Vector2d n = NormalOf(x.world.alpha);
      if (std::abs(n.dot(pos - x.world.point) - x.obs->d) > kOutlier) {
        use[k] = false;
        dropped = true;
      }
    }
    if (!dropped) break;
  }
  return out;
}

}  // namespace relplane::mapper
