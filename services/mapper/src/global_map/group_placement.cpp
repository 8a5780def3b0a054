#include "global_map/group_placement.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "eigen_solver_2d.hpp"
#include "global_map/relative_map.hpp"
#include "localisation/least_squares.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;
using geometry::Pose2;

// How much a line placed in a relative map by its orientation (Known::kLine) counts where the
// wall stands, `lever` metres along it from where its offset was measured: its fit's noise and a
// short piece's orientation bias over the lever, against `global_map.full_line`.
double LineWeight(double lever, double length, const MapperOptions& options) {
  const double bias = PieceBlurOfLength(length, options.fit);
  const double sigma = std::hypot(options.global_map.line_noise, lever * bias);
  const double full = options.global_map.full_line;
  return std::min(1.0, (full * full) / (sigma * sigma));
}

}  // namespace

double SightingOrientationWeight(const RltPlane& plane, int64_t iteration) {
  const auto& all = plane.Observations();
  const size_t i = plane.LowerBound(iteration);
  if (i >= all.size() || all[i].iteration != iteration) return 0.0;
  const ObservationTerms& terms = plane.Terms(i);  // OrientationWeight and PieceBlur
  return 1.0 / (1.0 / terms.weight + terms.blur * terms.blur);
}

Pose2 SolveGroupPlacement(const std::vector<GroupLink>& links, const Prior& prior_in,
                          const MapperOptions& options) {
  const double prior_weight = options.localisation.prior_weight;
  const Pose2& prior = prior_in.pose;
  double s = 0.0, c = 0.0;
  for (const GroupLink& l : links) {
    // Weighted by how well each wall's fit fixes its orientation, as in localisation: a door
    // jamb must not turn a group of walls metres long.
    const double w =
        l.orientation_weight > 0.0 ? l.orientation_weight : OrientationWeight(*l.plane);
    const double d = l.global.alpha - l.relative.alpha;
    s += w * std::sin(d), c += w * std::cos(d);
  }
  const double yaw = links.empty() ? prior.yaw : std::atan2(s, c);
  const Matrix2d rot = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  // A link's two lines are compared where the wall is (its latest sighting, as the pose then
  // put it), not at the point of the group's line: that is the foot of the perpendicular from
  // the edge the line was measured from (relative_map.cpp PlaceLine), which may lie metres along
  // the line, where the two lines' slightly different orientations part. `guess` is the
  // translation that looks the wall up in the group's frame: centimetres off move the point by
  // as much along the line, where the lines nearly agree.
  // Each line is weighed by how well its offset is known where the wall is: its fit's noise, and
  // a short piece's orientation bias (3 cm over its length) carried over the distance from the
  // edge it was measured from. A line known within `global_map.full_line` counts fully, as every
  // line did: a short pilaster side, fitted a degree off and measured from a recess corner metres
  // along its line, is centimetres off where it stands, and once it is its group's link it decides
  // the group's position along a hallway (the static edge that decided it before is only used where
  // the lines leave a direction open), moving the group and the pose back by as much.
  auto lines_at = [&](const Vector2d& guess, Matrix2d* a, Vector2d* b) {
    *a = Matrix2d::Zero();
    *b = Vector2d::Zero();
    for (const GroupLink& l : links) {
      if (l.relative.known == Known::kAngle || l.global.known == Known::kAngle) continue;
      const Vector2d n = NormalOf(l.global.alpha);
      Vector2d at = l.relative.point;
      double weight = 1.0;
      if (l.relative.known == Known::kLine && l.plane->latest_pose_known) {
        const Observation& latest = l.plane->Latest();
        const Vector2d wall = l.plane->latest_pose * (0.5 * (latest.edge[0] + latest.edge[1]));
        const Vector2d d = DirectionOf(l.relative.alpha);
        const double lever = d.dot(rot.transpose() * (wall - guess) - l.relative.point);
        at += d * lever;
        weight = LineWeight(lever, l.plane->Length(), options);
      }
      *a += weight * n * n.transpose();
      *b += weight * n * n.dot(l.global.point - rot * at);
    }
  };
  Matrix2d a;
  Vector2d b;
  lines_at(prior.Translation(), &a, &b);
  if (Eigen::SelfAdjointEigenSolver<Matrix2d>(a).eigenvalues()(0) >= 0.5) {
    lines_at(a.ldlt().solve(b), &a, &b);  // once more from where the lines put the group
  }
  // The prior only decides a direction the links leave open; along the directions its members'
  // lines span, those lines as seen with the heading the links give, its ends' placement along
  // the rest.
  Vector2d prior_t = prior.Translation();
  if (!prior_in.lines.empty()) {
    Matrix2d la = Matrix2d::Zero();
    Vector2d lb = Vector2d::Zero();
    for (const PriorLine& line : prior_in.lines) {
      const Vector2d n = NormalOf(yaw + line.member.alpha);
      // Weighed as the links' lines are: a door jamb's line, placed through a comparison with the
      // room's far wall where the two cross metres away, is centimetres off where the jamb
      // stands; counted as fully as the room's side walls, it moves the group, the pose and the
      // room's walls across the room when the group's basis changes. A direction only such
      // lines span, below `localisation.open_information`, is left to the ends' placement.
      double weight = 1.0;
      if (line.member.known == Known::kLine) {
        const Vector2d d = DirectionOf(line.member.alpha);
        const double lever =
            d.dot(rot.transpose() * (line.seen_point - prior.Translation()) - line.member.point);
        weight = LineWeight(lever, line.length, options);
      }
      la += weight * n * n.transpose();
      lb += weight * n * n.dot(line.seen_point - rot * line.member.point);
    }
    prior_t = SolveWithPrior(la, lb, prior_t, 0.0, 0.0, options.localisation.open_information);
  }
  // Lines are exact whatever the edges do; static edges are added only where the lines leave
  // a direction open (parallel walls), since an edge taken for static may not quite be. One
  // link's edge each, unless some agree with the prior along their wall and others lie more
  // than `global_map.edge_gate` from it: those are dropped. Where one link's piece in the group's
  // relative map is paired at the wrong end (a hallway wall whose end next to a recess is taken for
  // its far end), the two edges of a group's links put it a wall's length apart, and their mean
  // moves the group and the pose half that along the hallway in one iteration.
  Eigen::SelfAdjointEigenSolver<Matrix2d> eig(a);
  if (eig.eigenvalues()(0) < 0.5) {
    struct EdgeTie {
      Vector2d along;        // the wall's direction
      Vector2d translation;  // the group's translation the edge puts it at
    };
    std::vector<EdgeTie> ties;
    for (const GroupLink& l : links) {
      if (l.relative.known == Known::kAngle || l.global.known == Known::kAngle) continue;
      for (int e = 0; e < 2; ++e) {
        Vector2d rel_point, global_point;
        if (!EdgePoint(*l.plane, l.global, e, &global_point) ||
            !EdgePoint(*l.plane, l.relative, e, &rel_point)) {
          continue;
        }
        ties.push_back({DirectionOf(l.global.alpha), global_point - rot * rel_point});
        break;
      }
    }
    auto agrees = [&](const EdgeTie& tie) {
      return std::abs(tie.along.dot(tie.translation - prior_t)) <= options.global_map.edge_gate;
    };
    const bool any_agrees = std::any_of(ties.begin(), ties.end(), agrees);
    for (const EdgeTie& tie : ties) {
      if (any_agrees && !agrees(tie)) continue;
      a += tie.along * tie.along.transpose();
      b += tie.along * tie.along.dot(tie.translation);
    }
  }
  const Vector2d t =
      SolveWithPrior(a, b, prior_t, prior_weight, 0.5, options.localisation.open_information);
  return {t.x(), t.y(), yaw};
}

}  // namespace relplane::mapper
