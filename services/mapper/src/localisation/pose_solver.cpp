#include "localisation/pose_solver.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>

#include "comparison/comparison.hpp"
#include "eigen_solver_2d.hpp"
#include "global_map/relative_map.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

// The position's least squares: A x = b over unit directions and their offsets.
struct System {
  Matrix2d a = Matrix2d::Zero();
  Vector2d b = Vector2d::Zero();
  Matrix2d seen = Matrix2d::Zero();  // a without the priors: what the walls in view fix
  void Add(const Vector2d& dir, double value, double weight = 1.0) {
    AddPrior(dir, value, weight);
    seen += weight * dir * dir.transpose();
  }
  // An equation on the previous or predicted position, not on a wall in view.
  void AddPrior(const Vector2d& dir, double value, double weight) {
    a += weight * dir * dir.transpose();
    b += weight * dir * value;
  }
};

struct Heading {
  double yaw = 0.0;
  double sigma = 0.0;  // PoseEstimate::yaw_sigma
  double information = 0.0;
  int walls = 0;
};

// How much a mapped end `e` of `obs` counts against the learnt velocity's prediction when both
// are good to a wall end's noise: less as its samples land further apart along the wall.
double EndWeight(const LearnedFrustum& frustum, const Observation& obs, int e) {
  const double spacing = frustum.EdgeSpacing(obs.edge[e], obs.d);
  const double noise = frustum.EdgeNoise();
  return noise * noise / (noise * noise + spacing * spacing);
}

// The middle of the observed part of a wall (sensor frame).
Vector2d Middle(const Observation& obs) { return 0.5 * (obs.edge[0] + obs.edge[1]); }

// How far the middle of a sighting's part in view lies off its mapped line, seen from `pose`.
double Residual(const Sighting& x, const geometry::Pose2& pose) {
  const Vector2d n = NormalOf(x.world.alpha);
  return n.dot(pose * Middle(*x.obs) - x.world.point);
}

bool Placed(const Sighting& x) { return x.world.known != Known::kAngle; }

// §II.D the heading: the mean orientation difference between the walls seen and mapped,
// weighted by how well each wall's fit fixes its orientation (a short noisy wall, a door jamb,
// must not turn the heading of walls metres long). Its sigma combines the fit's and a short
// piece's bias, which the points' spread does not show.
Heading EstimateHeading(const std::vector<Sighting>& sightings, const std::vector<bool>& use,
                        const FitOptions& fit) {
  Heading h;
  double s = 0.0, c = 0.0;
  for (size_t k = 0; k < sightings.size(); ++k) {
    if (!use[k]) continue;
    const double w = OrientationWeight(*sightings[k].obs, fit);
    const double d = sightings[k].world.alpha - sightings[k].obs->Alpha();
    s += w * std::sin(d), c += w * std::cos(d), ++h.walls;
    const double sigma = std::hypot(1.0 / std::sqrt(w), PieceBlur(*sightings[k].obs, fit));
    h.information += 1.0 / (sigma * sigma);
  }
  if (h.walls == 0) return h;
  h.yaw = std::atan2(s, c);
  h.sigma = 1.0 / std::sqrt(h.information);
  return h;
}

// §II.E the walls' heading weighed against the motion model's (HeadingPrior) by their
// information; unchanged without a prior, or where the two disagree by more than `gate`
// combined sigmas.
Heading WithPrior(const Heading& walls, const HeadingPrior& prior, double gate) {
  if (!(prior.sigma > 0.0) || !(walls.sigma > 0.0)) return walls;
  const double apart = std::remainder(prior.yaw - walls.yaw, 2.0 * M_PI);
  if (std::abs(apart) > gate * std::hypot(walls.sigma, prior.sigma)) return walls;
  Heading out = walls;
  const double prior_information = 1.0 / (prior.sigma * prior.sigma);
  out.information = walls.information + prior_information;
  out.yaw = std::remainder(walls.yaw + apart * prior_information / out.information, 2.0 * M_PI);
  out.sigma = 1.0 / std::sqrt(out.information);
  return out;
}

// §II.D one equation per placed wall: the middle of the part in view lies on the wall's line,
// n . (c + R m) = n . P. Not the offset d the fit gives at the foot of the perpendicular from the
// sensor: a fit's offset is as good as its points only where they are.
void AddWallLines(const std::vector<Sighting>& sightings, const std::vector<bool>& use,
                  const Matrix2d& rot, System* sys, std::set<int64_t>* planes) {
  for (size_t k = 0; k < sightings.size(); ++k) {
    if (!use[k]) continue;
    const Sighting& x = sightings[k];
    if (!Placed(x)) continue;
    planes->insert(x.plane->Id());
    const Vector2d n = NormalOf(x.world.alpha);
    sys->Add(n, n.dot(x.world.point - rot * Middle(*x.obs)));
  }
}

// The inputs the §II.E motion model weighs wall ends against.
struct MotionContext {
  const geometry::Pose2& previous;
  const LearnedFrustum& frustum;
  const LocalisationOptions& options;
  int held;
  Prediction prediction;
  bool motion_known() const { return prediction.known; }
};

// A static edge seen now fixes the position along the wall (c + R e = P); used only where the
// lines leave a direction open, as an edge taken for static may drift (occlusion). With the
// motion known each end is weighed against the prediction, as in the motion model: an end far
// ahead at a grazing angle jumps by centimetres from frame to frame; and, as there, an end
// further from the prediction than its noise and the prediction's own error is not the wall's
// (an edge taken for static that is not where the map has the wall's end). Returns whether any
// end was added.
bool AddStaticEnds(const std::vector<Sighting>& sightings, const std::vector<bool>& use,
                   const Matrix2d& rot, const MotionContext& m, System* sys) {
  const LearnedFrustum& frustum = m.frustum;
  const bool motion_known = m.motion_known();
  bool ends_fix = false;
  for (size_t k = 0; k < sightings.size(); ++k) {
    const Sighting& x = sightings[k];
    if (!use[k] || !Placed(x)) continue;
    const Vector2d t = DirectionOf(x.world.alpha);
    for (int e = 0; e < 2; ++e) {
      Vector2d mapped;
      if (!x.plane->static_now[e] || x.plane->static_now_iteration != x.obs->iteration) continue;
      if (frustum.Clipped(x.obs->edge[e])) continue;
      if (!EdgePoint(*x.plane, x.world, e, &mapped)) continue;
      const double along = t.dot(mapped - rot * x.obs->edge[e]);
      if (motion_known && std::abs(along - t.dot(m.previous.Translation())) >=
                              m.options.edge_noise + m.prediction.sigma) {
        continue;
      }
      const double w = motion_known ? EndWeight(frustum, *x.obs, e) : 1.0;
      sys->Add(t, along, w);
      ends_fix = true;
    }
  }
  return ends_fix;
}

// §II.E motion model, where the walls leave the direction `open` open: a mapped wall end seen
// where the previous position predicts it; failing that, a wall end seen uncut from poses the
// walls fixed (a wall end stands still, §II.C, so where it is seen now shows how far the sensor
// moved along the wall, as the paper's growing partial plane does). Only the end the sensor
// samples finest: the spacing of its rays along a wall grows as r^2 / h (r the end's distance,
// h the wall's). Returns whether such an end moved the position (PoseEstimate::end_moved).
bool AddMotionModelEnds(const std::vector<Sighting>& sightings, const std::vector<bool>& use,
                        const Matrix2d& rot, const Vector2d& open, const MotionContext& m,
                        System* sys) {
  const LocalisationOptions& options = m.options;
  const bool motion_known = m.motion_known();
  bool finest = false;
  Vector2d finest_dir = Vector2d::Zero();
  double finest_along = 0.0, finest_spacing = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < sightings.size(); ++k) {
    const Sighting& x = sightings[k];
    if (!use[k] || !Placed(x)) continue;
    const Vector2d t = DirectionOf(x.world.alpha);
    for (int e = 0; e < 2; ++e) {
      Vector2d mapped;
      // Cut by the view (its bearing or its range) or seen past a nearer wall: no wall end.
      if (m.frustum.Clipped(x.obs->edge[e]) || x.obs->cut[e]) continue;
      const bool placed =
          x.world.known == Known::kPoint && EdgePoint(*x.plane, x.world, e, &mapped);
      if (!placed && !x.end_seen[e]) continue;
      const double along = t.dot((placed ? mapped : x.end[e]) - rot * x.obs->edge[e]);
      const double moved = along - t.dot(m.previous.Translation());
      if (placed) {
        if (std::abs(moved) >= options.end_gate) continue;
        // With the motion known the prediction is good to an end's noise and the velocity's
        // drift since the walls last fixed the position: an end further off is not the wall's.
        if (motion_known && std::abs(moved) >= m.options.edge_noise + m.prediction.sigma) {
          continue;
        }
        // With the motion known, an end whose samples land further apart than its noise says
        // less than the learnt velocity: it stands for frames and jumps a column.
        const double spacing = m.frustum.EdgeSpacing(x.obs->edge[e], x.obs->d);
        if (motion_known && spacing > 2.0 * m.options.edge_noise) continue;
        sys->Add(t, along, motion_known ? EndWeight(m.frustum, *x.obs, e) : 1.0);
        continue;
      }
      // Such an end is looked up only where no motion is known, so `previous` is the pose held
      // still, not a prediction: the sensor has since moved forwards by up to a step (the
      // platform drives forwards), never back, and by up to a step for each iteration held
      // still. An end outside that, by more than its noise, is seen past where it stands.
      const double forwards = t.dot(rot.col(0)) >= 0.0 ? moved : -moved;
      const double noise = m.options.edge_noise;
      const double reach = options.max_step * (1 + std::clamp(m.held, 0, options.max_held));
      if (forwards <= -noise || forwards >= reach + noise) continue;
      // Nor an end whose samples land further apart than its noise, as with the motion known:
      // the finest end in view may still be a coarse one.
      if (m.frustum.EdgeSpacing(x.obs->edge[e], x.obs->d) > 2.0 * noise) continue;
      const double h = std::abs(NormalOf(x.obs->Alpha()).dot(x.obs->edge[e]));
      const double spacing =
          h > 0.0 ? x.obs->edge[e].squaredNorm() / h : std::numeric_limits<double>::infinity();
      if (spacing < finest_spacing) {
        finest_spacing = spacing, finest_along = along;
        finest = true;
        finest_dir = t;
      }
    }
  }
  // With the motion known, the ends and the walls' lines weighed against the learnt velocity's
  // prediction by their noise: the prediction drifts by up to drift_rate an iteration since the
  // walls last fixed the position, a mapped end is good to `edge_noise` (the lines' unit weight
  // stands for that). Also with no end: walls that fix the open direction only weakly (a line
  // at angle θ to it turns its offset error into an error 1/sin θ times as large there) move the
  // position by their information against the prediction's, not outright.
  if (motion_known) {
    const double sigma = std::max(m.prediction.sigma, options.drift_rate);
    const double w = std::pow(m.options.edge_noise / sigma, 2);
    sys->AddPrior(open, open.dot(m.previous.Translation()), w);
  }
  // The platform drives forwards (as the learnt velocity takes it): along an open direction
  // across the heading the position stays where it was, whatever an end seen at another angle,
  // off by its sampling, says.
  const bool along_heading = std::abs(open.dot(rot.col(0))) >= options.along_heading;
  if (finest && along_heading) {
    sys->Add(finest_dir, finest_along);
    return true;
  }
  return false;
}

// One pose from the walls in `use` (§II.D), or the motion model's (§II.E) where they leave the
// position open.
PoseEstimate SolveOnce(const std::vector<Sighting>& sightings, const std::vector<bool>& use,
                       const Heading& heading, const MotionContext& m) {
  const LocalisationOptions& options = m.options;
  PoseEstimate out;
  out.yaw_sigma = heading.sigma;
  const Matrix2d rot = Eigen::Rotation2Dd(heading.yaw).toRotationMatrix();
  System sys;
  std::set<int64_t> planes;
  AddWallLines(sightings, use, rot, &sys, &planes);
  Eigen::SelfAdjointEigenSolver<Matrix2d> line_eig(sys.a);
  bool ends_fix = false;
  if (line_eig.eigenvalues()(0) < options.min_information) {
    ends_fix = AddStaticEnds(sightings, use, rot, m, &sys);
  }
  if (m.motion_known() && ends_fix) {
    // The previous pose, fixed by such ends, is good to about a centimetre, and the prediction
    // drifts on from there.
    const Vector2d open = line_eig.eigenvectors().col(0);
    const double sigma = std::max(options.tracked_prediction, m.prediction.sigma);
    sys.AddPrior(open, open.dot(m.previous.Translation()),
                 std::pow(m.options.edge_noise / sigma, 2));
  }
  Eigen::SelfAdjointEigenSolver<Matrix2d> eig(sys.a);
  const double information = eig.eigenvalues()(0);
  const bool tracking = planes.size() >= 2 && information >= options.min_information;
  if (!tracking) {
    out.end_moved = AddMotionModelEnds(sightings, use, rot, eig.eigenvectors().col(0), m, &sys);
  }
  // The previous position only decides a direction the walls leave open.
  const Vector2d pos = SolveWithPrior(sys.a, sys.b, m.previous.Translation(), options.prior_weight,
                                      options.min_information, options.open_information);
  out.pose = {pos.x(), pos.y(), heading.yaw};
  out.planes = static_cast<int>(planes.size());
  out.status = tracking ? PoseStatus::kTracking : PoseStatus::kMotionModel;
  out.position_information = sys.seen / (options.edge_noise * options.edge_noise);  // m^-2
  return out;
}

// The trial without the worst-fitting wall: kept where the rest still fix the position, agree
// among themselves, and put that wall off by more than a map's error.
bool TrialHolds(const std::vector<Sighting>& sightings, const std::vector<bool>& use, int suspect,
                const PoseEstimate& without, const LocalisationOptions& options) {
  bool agree = without.status == PoseStatus::kTracking &&
               std::abs(Residual(sightings[suspect], without.pose)) > options.misregistered;
  for (size_t k = 0; k < sightings.size() && agree; ++k) {
    if (use[k] && Placed(sightings[k])) {
      agree = std::abs(Residual(sightings[k], without.pose)) < options.suspect;
    }
  }
  return agree;
}

// One round of outlier rejection: a mis-registered wall must not drag the pose. Returns whether
// a wall was left out.
bool DropOutliers(const std::vector<Sighting>& sightings, const geometry::Pose2& pose,
                  const LocalisationOptions& options, std::vector<bool>* use) {
  bool dropped = false;
  for (size_t k = 0; k < sightings.size(); ++k) {
    const Sighting& x = sightings[k];
    if (!(*use)[k] || !Placed(x) || sightings.size() < 3) continue;
    if (std::abs(Residual(x, pose)) > options.outlier) {
      (*use)[k] = false;
      dropped = true;
    }
  }
  return dropped;
}

// The worst-fitting placed wall beyond `suspect` metres, where at least three walls fix the
// pose; -1 if none.
int WorstFit(const std::vector<Sighting>& sightings, const std::vector<bool>& use,
             const geometry::Pose2& pose, const LocalisationOptions& options) {
  int lines = 0, worst_k = -1;
  double worst = options.suspect;
  for (size_t k = 0; k < sightings.size(); ++k) {
    if (!use[k] || !Placed(sightings[k])) continue;
    ++lines;
    const double r = std::abs(Residual(sightings[k], pose));
    if (r > worst) worst = r, worst_k = static_cast<int>(k);
  }
  return lines < 3 ? -1 : worst_k;
}

// The trial without the worst-fitting wall failed: is a second wall off, the pose the first one
// dragged hiding it? Two walls misplaced by different amounts on one side can pull the pose
// onto the smaller error, so that without the worse one the other still disagrees. The trial
// without both holds where the rest still fix the position, agree among themselves and are more
// than the two left out, the first is off by more than a map's error and the second by more than
// `suspect` (§II.D: a mis-registered wall must not drag the pose). Returns the pose without
// both, or nothing.
std::optional<PoseEstimate> WithoutASecond(const std::vector<Sighting>& sightings,
                                           std::vector<bool>* use, int first,
                                           const PoseEstimate& without_first,
                                           const MotionContext& m, const FitOptions& fit) {
  const LocalisationOptions& options = m.options;
  const int second = WorstFit(sightings, *use, without_first.pose, options);
  if (second < 0) return std::nullopt;
  (*use)[second] = false;
  const PoseEstimate without = SolveOnce(sightings, *use, EstimateHeading(sightings, *use, fit), m);
  int kept = 0;
  bool holds = without.status == PoseStatus::kTracking &&
               std::abs(Residual(sightings[first], without.pose)) > options.misregistered &&
               std::abs(Residual(sightings[second], without.pose)) > options.suspect;
  for (size_t k = 0; k < sightings.size() && holds; ++k) {
    if (!(*use)[k] || !Placed(sightings[k])) continue;
    ++kept;
    holds = std::abs(Residual(sightings[k], without.pose)) < options.suspect;
  }
  if (holds && kept > 2) return without;
  (*use)[second] = true;
  return std::nullopt;
}

}  // namespace

Prediction LearntVelocity(int iterations, const LocalisationOptions& options) {
  if (iterations <= 0) return {};
  return {true, options.drift_rate * static_cast<double>(iterations)};
}

PoseEstimate Localise(const std::vector<Sighting>& sightings, const geometry::Pose2& previous,
                      const LearnedFrustum& frustum, const LocalisationOptions& options,
                      const FitOptions& fit, int held, const Prediction& prediction,
                      const HeadingPrior& heading_prior) {
  const MotionContext m{previous, frustum, options, held, prediction};
  PoseEstimate out;
  out.pose = previous;
  std::vector<bool> use(sightings.size(), true);
  int suspect = -1;           // the wall left out on trial, in the last round
  PoseEstimate with_suspect;  // the pose with it, kept unless the trial shows it off
  for (int round = 0; round < 3; ++round) {
    const Heading heading = EstimateHeading(sightings, use, fit);
    if (heading.walls == 0) {
      // Every wall left out as an outlier of the first round's pose: that pose came from walls
      // that disagree by metres (a mis-registered wall), so it is not kept either.
      out.pose = previous;
      out.status = PoseStatus::kLost;
      out.planes = 0;
      out.end_moved = false;
      out.position_information.setZero();
      return out;
    }
    out = SolveOnce(sightings, use, heading, m);
    if (suspect >= 0) {
      if (!TrialHolds(sightings, use, suspect, out, options)) {
        const std::optional<PoseEstimate> without =
            WithoutASecond(sightings, &use, suspect, out, m, fit);
        out = without ? *without : with_suspect;
      }
      break;
    }
    if (round == 0 && DropOutliers(sightings, out.pose, options, &use)) continue;
    // A wall registered as its neighbour a pilaster's depth away drags a position that three
    // walls fix by a third of that, and no wall is then as far off as `outlier`: the
    // worst-fitting one is tried without.
    if (out.status != PoseStatus::kTracking) {
      const Heading weighed = WithPrior(heading, heading_prior, options.heading_gate);
      if (weighed.yaw != heading.yaw) out = SolveOnce(sightings, use, weighed, m);
      break;
    }
    suspect = WorstFit(sightings, use, out.pose, options);
    if (suspect < 0) break;
    with_suspect = out;
    use[suspect] = false;
  }
  return out;
}

}  // namespace relplane::mapper
