#include "global_map/pose_graph.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "comparison/comparison.hpp"
#include "eigen_solver_2d.hpp"
#include "global_map/relative_map.hpp"
#include "localisation/pose_solver.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

// One plane's placement in two groups' relative maps.
struct Tie {
  int i = 0;
  int j = 0;
  const Placement* a = nullptr;
  const Placement* b = nullptr;
  const RltPlane* plane = nullptr;
  // Orientation (in group i's frame) of the normal the line residual is taken along: the wall's
  // own, or the pair's common one where all their lines are nearly parallel (OpenLines).
  double line_alpha = 0.0;
  // rad^2: how loosely each group's comparisons hold the plane's orientation (OrientationSpread).
  double alpha_variance = 0.0;
  // m^2: how far that looseness moves the line residual, which is taken between two points that
  // may lie metres apart along the line (LeverVariance).
  double lever_variance = 0.0;
};

// rad^2: how loosely the comparisons of group `g` hold member `id`'s orientation against the
// rest of the group: the inverse of their information (§II.C, a short piece's bias over its
// length included). A door jamb's face, a decimetre wide, is fitted degrees off, and its
// orientation in two groups' relative maps can disagree by more than half a degree; weighed as
// a wall's, that one tie turns every group after it when a loop's solve (§II.D) takes it in, and
// moves the walls of whole rooms by centimetres. A wall's comparisons hold it to a few
// thousandths of a radian.
//
// The basis is the group's frame (RefineOrientations holds it): its orientation there is off
// only by its own fit's bias (PieceBlur) while the group was seen, whatever its partners'. A
// group holding a long wall, its basis, and a jamb's face only: weighed by that one comparison,
// the anchor's tie to the next group is as loose as a jamb's, a loop's closing solve puts its
// turn there, and every later group turns about it. Where the basis is a jamb, its own bias
// keeps the tie loose: held as exact, a jamb's frame turns the next group by its fit's error.
double OrientationSpread(const GlobalMapInputs& in, const Grouping& grouping, int64_t g, int64_t id,
                         const FitOptions& fit) {
  const Group& group = grouping.groups[static_cast<size_t>(g)];
  double information = 0.0;
  double common = 0.0;  // iterations of the basis's longest comparison
  for (int64_t other : group.members) {
    if (other == id) continue;
    if (const Comparison* c = in.comparisons.Find(id, other)) {
      information += c->PieceInformation();
      common = std::max(common, c->Common());
    }
  }
  double spread = information > 0.0 ? 1.0 / information : 0.0;
  const auto plane = in.store.planes.find(id);
  if (id == group.relative.basis && common > 0.0 && plane != in.store.planes.end()) {
    const double blur = PieceBlurOfLength(plane->second.Length(), fit);
    spread = std::min(spread, blur * blur / common);
  }
  return spread;
}

// §II.D as in localisation: walls within ~11 degrees of parallel leave the direction along them
// open. Where every line two groups share is so, each line residual is taken along the lines'
// common normal: along its own, the slight angle between two walls turns a millimetre
// disagreement across them into metres along the hallway (a 0.2 degree angle between two
// hallway walls leaves one group's along-wall position "observed" some 300 times more weakly
// than across, and the solve can slide a whole leg of a hallway loop by metres).
void OpenLines(double open_information, std::vector<Tie>* ties) {
  std::map<std::pair<int, int>, Eigen::Matrix2d> information;
  for (const Tie& t : *ties) {
    if (t.a->known == Known::kAngle || t.b->known == Known::kAngle) continue;
    const Vector2d n = NormalOf(t.a->alpha);
    auto [it, inserted] = information.try_emplace({t.i, t.j}, Eigen::Matrix2d::Zero());
    it->second += n * n.transpose();
  }
  for (Tie& t : *ties) {
    t.line_alpha = t.a->alpha;
    auto it = information.find({t.i, t.j});
    if (it == information.end()) continue;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(it->second);
    if (eig.eigenvalues()(0) >= open_information) continue;
    Vector2d u = eig.eigenvectors().col(1);
    if (u.dot(NormalOf(t.a->alpha)) < 0.0) u = -u;
    t.line_alpha = std::atan2(u.x(), -u.y());  // NormalOf(line_alpha) == u
  }
}

// A line residual is taken across the wall between the point each group's relative map has on
// it, and those may lie metres apart along the wall: where a group places a member by its line
// alone, its point is wherever the comparison chain put the line's foot. An error in the
// member's orientation turns the residual by that distance times the error. A door jamb's face,
// the basis of one group and held by another's comparisons only as a line, can have its point
// there metres along from the jamb; its orientation a degree off then makes the two groups
// disagree across it by centimetres (5 m at 1 degree: 9 cm), and a loop's closing solve takes
// that in and moves the walls placed after it. Measured at the placements the solve starts
// from: the distance changes by millimetres during a solve.
void LeverVariance(const std::vector<geometry::Pose2>& x, std::vector<Tie>* ties) {
  for (Tie& t : *ties) {
    const Vector2d along = DirectionOf(x[t.i].yaw + t.line_alpha);
    const double lever = along.dot(x[t.i] * t.a->point - x[t.j] * t.b->point);
    t.lever_variance = t.alpha_variance * lever * lever;
  }
}

// Ties between consecutive groups (by index) holding the same rltplane with a known placement.
std::vector<Tie> CollectTies(const GlobalMapInputs& in, const Grouping& grouping,
                             double open_information, const FitOptions& fit) {
  std::vector<Tie> ties;
  for (const auto& [id, plane] : in.store.planes) {
    int previous = -1;
    for (int64_t g : plane.groups) {
      if (g < 0 || g >= static_cast<int64_t>(grouping.groups.size())) continue;
      const auto& members = grouping.groups[g].relative.members;
      if (!members.count(id)) continue;
      if (previous >= 0 && previous != g) {
        Tie tie{previous, static_cast<int>(g), &grouping.groups[previous].relative.members.at(id),
                &members.at(id), &plane};
        tie.alpha_variance = OrientationSpread(in, grouping, previous, id, fit) +
                             OrientationSpread(in, grouping, g, id, fit);
        ties.push_back(tie);
      }
      previous = static_cast<int>(g);
    }
  }
  OpenLines(open_information, &ties);
  return ties;
}

// What hard chaining (§II.D) measured of a group from the one before where their ties leave it
// open. A group that shares no wall end with the one before (turning in place at a corner, the
// walls before the turn gone from view before the next ones came in) is chained on from the
// pose, which the motion model holds still (§II.E); the ties know nothing of that direction, and
// with only the weak prior to hold it a loop's error goes all into those directions at corners,
// and each leg keeps the drift it made along it (after the loop closes, the far end wall of a
// leg stays short by that drift). Where the ties observe a direction the chain only repeats
// them, and is left out. Not for a group a loop placed from older groups (it has loop
// evidence): its chain does not run from the group before.
struct ChainPrior {
  std::vector<Vector2d> open;  // world directions of the position the ties leave open
  bool yaw = false;            // no tie turns the two groups
};

std::vector<ChainPrior> ChainPriors(const Grouping& grouping, const std::vector<Tie>& ties,
                                    const std::vector<geometry::Pose2>& x,
                                    double open_information) {
  const int n = static_cast<int>(grouping.groups.size());
  std::vector<ChainPrior> chain(n);
  std::vector<Eigen::Matrix2d> information(n, Eigen::Matrix2d::Zero());
  std::vector<bool> turned(n, false);
  for (const Tie& t : ties) {
    if (t.j != t.i + 1) continue;
    turned[t.j] = true;
    if (t.a->known == Known::kAngle || t.b->known == Known::kAngle) continue;
    const Vector2d normal = NormalOf(x[t.i].yaw + t.a->alpha);
    information[t.j] += normal * normal.transpose();
  }
  for (int k = 1; k < n; ++k) {
    if (grouping.groups[k].loop_evidence > 0) continue;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(information[k]);
    for (int e = 0; e < 2; ++e) {
      if (eig.eigenvalues()(e) < open_information) {
        chain[k].open.push_back(eig.eigenvectors().col(e));
      }
    }
    chain[k].yaw = !turned[k];
  }
  return chain;
}

// The pose ties whose groups still have the frames they were made in (PoseTie).
std::vector<const PoseTie*> CurrentPoseTies(const Grouping& grouping, const WorldMap& world) {
  std::vector<const PoseTie*> current;
  const auto n = static_cast<int64_t>(grouping.groups.size());
  auto same_frame = [&grouping](int64_t g, int64_t basis, int ref) {
    const RelativeMap& map = grouping.groups[static_cast<size_t>(g)].relative;
    return map.basis == basis && map.BasisRef() == ref;
  };
  for (const PoseTie& t : world.pose_ties) {
    if (t.a_group < 0 || t.a_group >= n || t.b_group < 0 || t.b_group >= n) continue;
    if (!same_frame(t.a_group, t.a_basis, t.a_ref) || !same_frame(t.b_group, t.b_basis, t.b_ref)) {
      continue;
    }
    current.push_back(&t);
  }
  return current;
}

// d/dyaw of R(yaw) p.
Vector2d RotDerivative(double yaw, const Vector2d& p) {
  return Eigen::Rotation2Dd(yaw) * Vector2d(-p.y(), p.x());
}

struct Normal {
  std::vector<Eigen::Triplet<double>> h;
  Eigen::VectorXd g;
  double cost = 0.0;
  double robust = 3.0;  // PoseGraphOptions::robust
  // The largest squared normalised residual added (before the robust kernel).
  double worst = 0.0;
  // Adds one residual r (weight w) with Jacobian entries over the two nodes' (x, y, yaw).
  // The Cauchy kernel (scale `robust` sigmas) weighs the residual down when it is an outlier: a
  // tie through a plane misplaced in one group's relative map must not bend the whole loop.
  void Add(double r, double w, int i, const Eigen::Vector3d& ji, int j, const Eigen::Vector3d& jj) {
    worst = std::max(worst, w * r * r);
    const double s = w * r * r / (robust * robust);
    cost += robust * robust * std::log1p(s);
    w /= 1.0 + s;
    const int idx[2] = {3 * i, 3 * j};
    const Eigen::Vector3d* jac[2] = {&ji, &jj};
    for (int u = 0; u < 2; ++u) {
      g.segment<3>(idx[u]) += w * r * *jac[u];
      for (int v = 0; v < 2; ++v) {
        for (int p = 0; p < 3; ++p) {
          for (int q = 0; q < 3; ++q) {
            const double value = w * (*jac[u])(p) * (*jac[v])(q);
            if (value != 0.0) h.emplace_back(idx[u] + p, idx[v] + q, value);
          }
        }
      }
    }
  }
};

// The normalised cost and its normal equations at the current placements.
Normal Linearise(const std::vector<Tie>& ties, const std::vector<const PoseTie*>& pose_ties,
                 const std::vector<ChainPrior>& chain, const std::vector<geometry::Pose2>& x,
                 const std::vector<geometry::Pose2>& x0, const PoseGraphOptions& options) {
  const int n = static_cast<int>(x.size());
  Normal eq;
  eq.robust = options.robust;
  eq.g = Eigen::VectorXd::Zero(3 * n);
  eq.h.reserve(ties.size() * 3 * 36 + 3 * n);
  const double wa = 1.0 / (options.angle_sigma * options.angle_sigma);
  const double base = options.position_sigma * options.position_sigma;
  for (const Tie& t : ties) {
    const geometry::Pose2& pi = x[t.i];
    const geometry::Pose2& pj = x[t.j];
    // Each placement is as good as the static pairings that chained it to its group's basis
    // (§II.C: their spread over the common interval). A wall end seen at a grazing angle lies
    // where the sensor's rays last hit it, centimetres short of the end and jumping as the
    // sensor moves: weighed like any other tie, its few centimetres turn whole groups by tenths
    // of a degree where the ties otherwise agree within hundredths, since a turn moves a point
    // metres away from the group's frame at little cost in orientation.
    const double wp = 1.0 / (base + t.a->variance + t.b->variance);
    const double wl = 1.0 / (1.0 / wp + t.lever_variance);
    const double alpha = pi.yaw + t.a->alpha;
    // The orientation, as far as both groups' comparisons hold it (OrientationSpread).
    eq.Add(geometry::WrapAngle(alpha - (pj.yaw + t.b->alpha)), 1.0 / (1.0 / wa + t.alpha_variance),
           t.i, {0, 0, 1}, t.j, {0, 0, -1});
    if (t.a->known == Known::kAngle || t.b->known == Known::kAngle) continue;
    // The line: the two placements' points lie on one world line. Its normal turns with group
    // i (d n / d yaw = t): the two points may lie metres apart along the wall, and without that
    // term the steps turned the groups wrongly.
    const double line = pi.yaw + t.line_alpha;
    const Vector2d across = NormalOf(line), along = DirectionOf(line);
    const Vector2d diff = pi * t.a->point - pj * t.b->point;
    eq.Add(
        across.dot(diff), wl, t.i,
        {across.x(), across.y(), along.dot(diff) + across.dot(RotDerivative(pi.yaw, t.a->point))},
        t.j, {-across.x(), -across.y(), -across.dot(RotDerivative(pj.yaw, t.b->point))});
    // The static edge: the same wall end in both.
    if (t.a->known != Known::kPoint || t.b->known != Known::kPoint) continue;
    const Vector2d nrm = NormalOf(alpha), dir = DirectionOf(alpha);
    Vector2d qb;
    if (!EdgePoint(*t.plane, *t.b, t.a->ref, &qb)) continue;
    const Vector2d qa = t.a->point;
    const Vector2d edge_diff = pi * qa - pj * qb;
    // d t / d yaw = -n.
    eq.Add(dir.dot(edge_diff), wp, t.i,
           {dir.x(), dir.y(), -nrm.dot(edge_diff) + dir.dot(RotDerivative(pi.yaw, qa))}, t.j,
           {-dir.x(), -dir.y(), -dir.dot(RotDerivative(pj.yaw, qb))});
  }
  // Loops closed by backtracking: one sensor pose as each of two groups has it (PoseTie).
  const double wpose = 1.0 / (options.pose_tie_sigma * options.pose_tie_sigma);
  const double wyaw = 1.0 / (options.pose_tie_angle_sigma * options.pose_tie_angle_sigma);
  for (const PoseTie* t : pose_ties) {
    const int i = static_cast<int>(t->a_group), j = static_cast<int>(t->b_group);
    const geometry::Pose2& pi = x[i];
    const geometry::Pose2& pj = x[j];
    const Vector2d diff = pi * t->a.Translation() - pj * t->b.Translation();
    const Vector2d di = RotDerivative(pi.yaw, t->a.Translation());
    const Vector2d dj = RotDerivative(pj.yaw, t->b.Translation());
    if (t->has_open) {
      // Across the open direction only (it turns with group i).
      const Vector2d w = NormalOf(pi.yaw + t->open_alpha);
      const Vector2d dw = RotDerivative(0.0, w);  // d w / d yaw_i
      eq.Add(w.dot(diff), wpose, i, {w.x(), w.y(), w.dot(di) + dw.dot(diff)}, j,
             {-w.x(), -w.y(), -w.dot(dj)});
    } else {
      eq.Add(diff.x(), wpose, i, {1, 0, di.x()}, j, {-1, 0, -dj.x()});
      eq.Add(diff.y(), wpose, i, {0, 1, di.y()}, j, {0, -1, -dj.y()});
    }
    eq.Add(geometry::WrapAngle(pi.yaw + t->a.yaw - pj.yaw - t->b.yaw), wyaw, i, {0, 0, 1}, j,
           {0, 0, -1});
  }
  // Each group where the chain put it from the one before (§II.D hard chaining), along what the
  // ties between the two leave open (ChainPrior): the motion model's pose, weighed as a PoseTie's.
  for (int k = 1; k < n; ++k) {
    const ChainPrior& link = chain[k];
    if (!link.yaw && link.open.empty()) continue;
    const geometry::Pose2 rel = x0[k - 1].Inverse() * x0[k];
    const geometry::Pose2& pi = x[k - 1];
    const geometry::Pose2& pj = x[k];
    const Vector2d diff = pi * rel.Translation() - pj.Translation();
    const Vector2d di = RotDerivative(pi.yaw, rel.Translation());
    for (const Vector2d& u : link.open) {
      eq.Add(u.dot(diff), wpose, k - 1, {u.x(), u.y(), u.dot(di)}, k, {-u.x(), -u.y(), 0});
    }
    if (link.yaw) {
      eq.Add(geometry::WrapAngle(pi.yaw + rel.yaw - pj.yaw), wyaw, k - 1, {0, 0, 1}, k, {0, 0, -1});
    }
  }
  // Each group's chained placement as a weak prior (the gauge where ties leave a direction
  // open); group 0 is anchored.
  const double wprior = 1.0 / (options.prior_sigma * options.prior_sigma);
  for (int k = 0; k < n; ++k) {
    const double w = k == 0 ? 1e12 : wprior;
    const double r[3] = {x[k].x - x0[k].x, x[k].y - x0[k].y,
                         geometry::WrapAngle(x[k].yaw - x0[k].yaw)};
    for (int p = 0; p < 3; ++p) {
      Eigen::Vector3d jac = Eigen::Vector3d::Zero();
      jac(p) = 1.0;
      eq.cost += w * r[p] * r[p];
      eq.g(3 * k + p) += w * r[p];
      eq.h.emplace_back(3 * k + p, 3 * k + p, w);
    }
  }
  return eq;
}

}  // namespace

int GroupLoopEvidence(const PlaneStore& store, const Grouping& grouping, size_t g, int min_span) {
  int evidence = 0;
  const auto& members = grouping.groups[g].relative.members;
  for (const auto& [id, placed] : members) {
    auto plane = store.planes.find(id);
    if (plane == store.planes.end()) continue;
    // The latest earlier group that places the plane too.
    const Placement* earlier = nullptr;
    int64_t earlier_group = -1;
    for (int64_t h : plane->second.groups) {
      if (h < 0 || h >= static_cast<int64_t>(g)) continue;
      auto it = grouping.groups[h].relative.members.find(id);
      if (it != grouping.groups[h].relative.members.end() && h > earlier_group) {
        earlier = &it->second;
        earlier_group = h;
      }
    }
    if (earlier != nullptr && static_cast<int64_t>(g) - earlier_group > min_span) {
      evidence += 1 + std::min(static_cast<int>(placed.known), static_cast<int>(earlier->known));
    }
  }
  return evidence;
}

PoseGraphResult OptimiseGroupPlacements(const GlobalMapInputs& in, const WorldMap& world,
                                        const MapperOptions& mapper_options, Grouping& grouping) {
  const PoseGraphOptions& options = mapper_options.graph;
  const double open_information = mapper_options.localisation.open_information;
  PoseGraphResult result;
  const int n = static_cast<int>(grouping.groups.size());
  if (n < 2) return result;
  std::vector<Tie> ties = CollectTies(in, grouping, open_information, mapper_options.fit);
  const std::vector<const PoseTie*> pose_ties = CurrentPoseTies(grouping, world);
  result.ties = static_cast<int>(ties.size() + pose_ties.size());
  // The priors are centred on each group's chained placement (§II.D), which a solve leaves as
  // it was, not on where the last solve left the group: that placement already holds the ties,
  // so a prior centred on it counted them again at every solve, and each solve moved a direction
  // the ties hardly observe a little further towards where the ties alone put it, noise and all
  // (over laps of a loop, a centimetre or two a solve adds up to decimetres, and walls are
  // mapped twice). The solve still starts from the placements.
  std::vector<geometry::Pose2> x(n), x0(n);
  for (int k = 0; k < n; ++k) {
    Group& group = grouping.groups[k];
    if (!group.has_chained) {
      group.chained = group.placement;
      group.has_chained = true;
    }
    x[k] = group.placement;
    x0[k] = group.chained;
  }
  LeverVariance(x, &ties);
  Eigen::SparseMatrix<double> h(3 * n, 3 * n);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  const std::vector<ChainPrior> chain = ChainPriors(grouping, ties, x, open_information);
  // A loop spreads an error only where there is one: with every tie within `consistent` of its
  // sigma at the chained placements, the chain already holds the groups' shared planes within
  // the ties' noise, and a solve would only trade the chain's errors for the ties'. The groups
  // go back to the chain. A loop closed by backtracking (§II.A end) is solved all the same: its
  // pose ties were made only where the closing pose jumped (tie_min_jump, tie_min_turn).
  if (pose_ties.empty()) {
    const Normal at_chain = Linearise(ties, pose_ties, chain, x0, x0, options);
    if (at_chain.worst <= options.consistent * options.consistent) {
      result.consistent = true;
      result.cost_before = Linearise(ties, pose_ties, chain, x, x0, options).cost;
      result.cost_after = at_chain.cost;
      for (int k = 0; k < n; ++k) grouping.groups[k].placement = x0[k];
      return result;
    }
  }
  Normal eq = Linearise(ties, pose_ties, chain, x, x0, options);
  result.cost_before = eq.cost;
  // Levenberg-Marquardt: a step that does not lower the cost is refused and the next one damped
  // harder. Plain Gauss-Newton overshot: through the robust kernel and the groups the ties
  // leave nearly free, its first step can raise the cost several times over, even on a
  // consistent map, and the iterations then end in another minimum metres away.
  double damping = options.initial_damping;
  for (int iter = 0; iter < options.max_iterations; ++iter) {
    h.setFromTriplets(eq.h.begin(), eq.h.end());
    for (int k = 0; k < 3 * n; ++k) h.coeffRef(k, k) *= 1.0 + damping;
    solver.compute(h);  // the pattern may change between iterations (exact zeros are left out)
    if (solver.info() != Eigen::Success) break;
    const Eigen::VectorXd step = solver.solve(-eq.g);
    if (!step.allFinite()) break;
    std::vector<geometry::Pose2> next = x;
    for (int k = 1; k < n; ++k) {
      next[k].x += step(3 * k);
      next[k].y += step(3 * k + 1);
      next[k].yaw = geometry::WrapAngle(next[k].yaw + step(3 * k + 2));
    }
    result.iterations = iter + 1;
    Normal next_eq = Linearise(ties, pose_ties, chain, next, x0, options);
    if (next_eq.cost >= eq.cost) {
      damping *= 10.0;
      continue;
    }
    x = std::move(next);
    eq = std::move(next_eq);
    damping /= 10.0;
    if (step.cwiseAbs().maxCoeff() < 1e-5) break;  // m and rad: far below the map's noise
  }
  result.cost_after = eq.cost;
  // Keep the result only if it explains the ties better (a failed solve leaves the map alone).
  if (result.cost_after < result.cost_before) {
    for (int k = 0; k < n; ++k) grouping.groups[k].placement = x[k];
  }
  return result;
}

}  // namespace relplane::mapper
