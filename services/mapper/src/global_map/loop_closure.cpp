#include "global_map/loop_closure.hpp"

#include <algorithm>
#include <cmath>

#include "eigen_solver_2d.hpp"

namespace relplane::mapper {

ClosingLoop NoteClosing(const std::vector<Sighting>& chain, const geometry::Pose2& pose,
                        int64_t oldest, const WorldMap& world, const Trajectory& trajectory,
                        const MotionModel& motion, int64_t previous_iteration,
                        const geometry::Pose2& previous_pose, const MapperOptions& options) {
  ClosingLoop loop;
  if (oldest < 0 || chain.empty()) return loop;
  // The pose is the chain's only where every wall it came from was placed by a group well after
  // the re-seen one: once the old walls are in view again they set it too.
  int64_t newest = -1;
  Eigen::Matrix2d information = Eigen::Matrix2d::Zero();
  for (const Sighting& s : chain) {
    auto by = world.placed_by.find(s.plane->Id());
    if (by == world.placed_by.end() || by->second - oldest <= options.grouping.recent_groups)
      return loop;
    newest = std::max(newest, by->second);
    if (s.world.known == Known::kAngle) continue;
    const Eigen::Vector2d n = NormalOf(s.world.alpha);
    information += n * n.transpose();
  }
  // Where the chain's walls leave a direction open the pose is the motion model's along it
  // (§II.E): as good as the sensor's position while it turns on the spot (held still), but only
  // a learnt velocity's guess while it moves. The tie then holds the two groups across that
  // direction only, or not at all.
  const auto& poses = trajectory.poses;
  auto before = poses.lower_bound(previous_iteration - 1);
  const bool turning =
      before != poses.end() && before->first < previous_iteration &&
      motion.Turning(before->second, previous_pose, previous_iteration - before->first);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(information);
  if (!turning && eig.eigenvalues()(1) < options.localisation.open_information)
    return loop;  // both directions open
  if (!turning && eig.eigenvalues()(0) < options.localisation.open_information) {
    loop.open = true;
    const Eigen::Vector2d u = eig.eigenvectors().col(0);
    loop.open_alpha = std::atan2(u.y(), u.x());
  }
  loop.closing = true;
  loop.pose = pose;
  loop.from = newest;
  loop.to = oldest;
  return loop;
}

bool AddPoseTie(const ClosingLoop& loop, const PoseEstimate& estimate,
                const PoseGraphOptions& options, const Grouping& grouping, WorldMap& world) {
  if (!loop.closing || estimate.status != PoseStatus::kTracking) return false;
  const Group& from = grouping.groups.at(static_cast<size_t>(loop.from));
  const Group& to = grouping.groups.at(static_cast<size_t>(loop.to));
  // A loop that closes where the chain already has the sensor has nothing to spread: no tie, and
  // the graph is not solved for it.
  Eigen::Vector2d jump(estimate.pose.x - loop.pose.x, estimate.pose.y - loop.pose.y);
  if (loop.open) jump = NormalOf(loop.open_alpha).dot(jump) * NormalOf(loop.open_alpha);
  if (jump.norm() < options.tie_min_jump &&
      std::abs(geometry::WrapAngle(estimate.pose.yaw - loop.pose.yaw)) < options.tie_min_turn) {
    return false;
  }
  PoseTie tie;
  tie.a_group = loop.from;
  tie.b_group = loop.to;
  tie.a_basis = from.relative.basis;
  tie.b_basis = to.relative.basis;
  tie.a_ref = from.relative.BasisRef();
  tie.b_ref = to.relative.BasisRef();
  tie.has_open = loop.open;
  tie.open_alpha = geometry::WrapAngle(loop.open_alpha - from.placement.yaw);
  tie.a = from.placement.Inverse() * loop.pose;
  tie.b = to.placement.Inverse() * estimate.pose;
  // A few per loop driven (only the first sighting of an old wall again closes it): bounded all
  // the same, for runs of hours.
  if (world.pose_ties.size() >= static_cast<size_t>(options.max_pose_ties)) {
    world.pose_ties.erase(world.pose_ties.begin());
  }
  world.pose_ties.push_back(tie);
  ++world.pose_ties_made;
  return true;
}

}  // namespace relplane::mapper
