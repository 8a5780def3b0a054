#include "relplane/mapper/localisation.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <set>

#include "relplane/mapper/comparison.hpp"
#include "relplane/mapper/relative_map.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

// rad: orientation sigma every wall has whatever its fit says (the map's own error), so the
// best-fitting walls do not take all the weight.
constexpr double kOrientationFloor = 0.001;

// How much a mapped end `e` of `obs` counts against the learnt velocity's prediction when both
// are good to a wall end's noise: less as its samples land further apart along the wall.
double EndWeight(const LearnedFrustum& frustum, const Observation& obs, int e) {
  const double spacing = frustum.EdgeSpacing(obs.edge[e], obs.d);
  const double noise = LearnedFrustum::kEdgeNoise;
  return noise * noise / (noise * noise + spacing * spacing);
}

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

// The middle of the observed part of a wall (sensor frame).
Vector2d Middle(const Observation& obs) { return 0.5 * (obs.edge[0] + obs.edge[1]); }

// How far the middle of a sighting's part in view lies off its mapped line, seen from `pose`.
double Residual(const Sighting& x, const geometry::Pose2& pose) {
  const Vector2d n = NormalOf(x.world.alpha);
  return n.dot(pose * Middle(*x.obs) - x.world.point);
}

}  // namespace

void LearnedFrustum::Observe(const Eigen::Vector2d& edge) {
  const double bearing = std::abs(std::atan2(edge.y(), edge.x()));
  max_bearing_ = std::max(max_bearing_, bearing);
  const int bin = std::min(kBins - 1, static_cast<int>(bearing / kBinWidth));
  ++counts_[bin];
  // The pile-up: the fullest bin in the outer part of what has been seen.
  if (bin > mode_bin_ && counts_[bin] >= counts_[mode_bin_]) mode_bin_ = bin;
  if (counts_[bin] > counts_[mode_bin_] && bin * kBinWidth > 0.5 * max_bearing_) mode_bin_ = bin;
  const int rbin = std::min(kRangeBins - 1, static_cast<int>(edge.norm() / kRangeBin));
  ++range_counts_[rbin];
  max_range_bin_ = std::max(max_range_bin_, rbin);
  if (++observed_ % 64 == 0) UpdateRangeLimit();
}

void LearnedFrustum::ObserveSampling(const Observation& obs) {
  // Walls with plenty of points only: a sliver's extent says little of its points' spacing.
  constexpr int kMinSupport = 500;
  constexpr int kSlices = 16;
  constexpr int kMinObserved = 30;
  if (obs.support < kMinSupport || !(obs.z_max > obs.z_min)) return;
  // The solid angle of the wall's rectangle between its edges and heights: over slices along
  // it, the bearing each spans times the sine of the elevation at its top less at its bottom.
  double omega = 0.0;
  for (int k = 0; k < kSlices; ++k) {
    const Vector2d a = obs.edge[0] + (obs.edge[1] - obs.edge[0]) * (k / double(kSlices));
    const Vector2d b = obs.edge[0] + (obs.edge[1] - obs.edge[0]) * ((k + 1) / double(kSlices));
    const double span =
        std::abs(std::remainder(std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x()), 2.0 * M_PI));
    const double r = 0.5 * (a.norm() + b.norm());
    omega += span * (obs.z_max / std::hypot(obs.z_max, r) - obs.z_min / std::hypot(obs.z_min, r));
  }
  if (!(omega > 0.0)) return;
  const double log_per_ray = std::log(omega / obs.support);
  const int bin = static_cast<int>((log_per_ray - kStepLogMin) / kStepBin);
  if (bin < 0 || bin >= kStepBins) return;
  ++step_counts_[bin];
  ++steps_observed_;
  if (steps_observed_ < kMinObserved || steps_observed_ % 16 != 0) return;
  // The median: a wall with a door, or partly hidden, spans more than its points cover.
  int below = 0;
  for (int b = 0; b < kStepBins; ++b) {
    below += step_counts_[b];
    if (2 * below >= steps_observed_) {
      step_ = std::sqrt(std::exp(kStepLogMin + (b + 0.5) * kStepBin));
      break;
    }
  }
}

double LearnedFrustum::AngularStep() const { return step_; }

double EdgeSpacing(double step, const Eigen::Vector2d& edge, double d) {
  if (step <= 0.0) return 0.0;
  return step * edge.squaredNorm() / std::max(d, 0.05);
}

double LearnedFrustum::EdgeSpacing(const Eigen::Vector2d& edge, double d) const {
  return mapper::EdgeSpacing(step_, edge, d);
}

void LearnedFrustum::UpdateRangeLimit() {
  // The farthest pile-up that stands out from the distances just below it with next to nothing
  // beyond: edges cut by the range are the farthest the sensor reports. The fullest bin is not
  // it: a sensor turning in place sees one wall end at one distance for many frames, and such an
  // interior pile outgrew the range's (3.92 m against 5.92-5.98 m on a 6 m sensor) and hid it,
  // so that range-cut ends passed for wall ends. Once learnt, a limit is kept until a pile
  // farther out replaces it: the edges past a range pile are range cuts too (seen at other
  // angles, a hallway's walls all cut 0.3 m short of an 8 m range), not wall ends.
  constexpr int kSpread = 3;  // bins either side of the pile's peak that still belong to it
  constexpr int kBelow = 25;  // bins (0.5 m) below it to compare with
  int beyond = 0;             // edges past the candidate pile
  for (int peak = max_range_bin_; peak >= 0; --peak) {
    if (peak + kSpread + 1 <= max_range_bin_) beyond += range_counts_[peak + kSpread + 1];
    if (50 * beyond > observed_) return;  // no pile further in has next to nothing beyond it
    if (range_counts_[peak] < kMinPile) continue;
    int pile = 0, below = 0;
    for (int b = std::max(0, peak - kSpread); b <= std::min(kRangeBins - 1, peak + kSpread); ++b) {
      pile += range_counts_[b];
    }
    for (int b = std::max(0, peak - kSpread - kBelow); b < peak - kSpread; ++b) {
      below += range_counts_[b];
    }
    const double below_per_bin = static_cast<double>(below) / kBelow;
    if (range_counts_[peak] > 5.0 * below_per_bin && beyond <= pile / 50) {
      // The farthest full bin may be the pile's upper flank (edge noise): its fullest bin is
      // where the range cuts.
      int mode = peak;
      for (int b = std::max(0, peak - kSpread); b < peak; ++b) {
        if (range_counts_[b] > range_counts_[mode]) mode = b;
      }
      range_limit_ = (mode + kSpread + 1) * kRangeBin;
      return;
    }
  }
}

double LearnedFrustum::Limit() const {
  if (counts_[mode_bin_] < kMinPile) return max_bearing_;
  return std::min(max_bearing_, (mode_bin_ + 1) * kBinWidth);
}

double LearnedFrustum::RangeLimit() const { return range_limit_; }

bool LearnedFrustum::Clipped(const Eigen::Vector2d& edge) const {
  // The edge's bearing is uncertain by its position noise over its range.
  const double range = edge.norm();
  const double margin = kBearingMargin + std::atan2(kEdgeNoise, range);
  if (std::abs(std::atan2(edge.y(), edge.x())) > Limit() - margin) return true;
  return range > RangeLimit() - kEdgeNoise - 4 * kRangeBin;
}

bool LearnedFrustum::Clipped(const Eigen::Vector2d& edge, const Eigen::Vector2d& other) const {
  if (Clipped(edge)) return true;
  // Rays meeting a wall at a glancing angle sample it sparsely along its length: the last sample
  // within the range lies short of it by up to a sample's spacing, which grows as the rays graze
  // the wall (a side wall 2.25 m off a 6 m sensor's path was first seen range-cut 5.93 m away,
  // short of where the distance alone says cut, and put a group 1.56 m off). The edge is cut if
  // the wall past it reaches that distance within the bearing margin, as seen from the sensor:
  // the next sample along it may have been out of range (§II.C: no static edge).
  const double range = RangeLimit() - kEdgeNoise - 4 * kRangeBin;  // as above
  const double length = (edge - other).norm();
  if (!std::isfinite(range) || length <= 0.0) return false;
  const Eigen::Vector2d t = (edge - other) / length;  // along the wall, past this edge
  const double along = t.dot(edge);  // from the foot of the perpendicular from the sensor
  if (along <= 0.0) return false;    // the wall comes nearer past this edge
  const double normal = std::abs(t.x() * edge.y() - t.y() * edge.x());
  if (normal >= range) return false;
  const double gap = std::acos(normal / range) - std::atan2(along, normal);
  return gap < kBearingMargin + std::atan2(kEdgeNoise, edge.norm());
}

double OrientationSigma(const Observation& obs) {
  if (obs.rms <= 0.0) return 0.0;
  if (obs.support < 3) return std::numeric_limits<double>::infinity();
  const double spread = obs.Length() * std::sqrt(static_cast<double>(obs.support) / 12.0);
  return spread > 0.0 ? obs.rms / spread : std::numeric_limits<double>::infinity();
}

double OrientationWeight(const Observation& obs) {
  const double sigma = std::min(OrientationSigma(obs), 1.0);
  return 1.0 / (sigma * sigma + kOrientationFloor * kOrientationFloor);
}

double OrientationWeight(const RltPlane& plane) { return plane.BestOrientationWeight(); }

Eigen::Vector2d SolveWithPrior(const Eigen::Matrix2d& a, const Eigen::Vector2d& b,
                               const Eigen::Vector2d& previous, double prior_weight,
                               double min_information) {
  // Solved along the eigenvectors of a, so the open direction is decoupled from the others.
  Eigen::SelfAdjointEigenSolver<Matrix2d> eig(a);
  const double prior = eig.eigenvalues()(0) < min_information ? prior_weight : 0.0;
  Vector2d pos = Vector2d::Zero();
  for (int k = 0; k < 2; ++k) {
    const Vector2d v = eig.eigenvectors().col(k);
    const double lambda = eig.eigenvalues()(k);
    pos += v * (lambda < kOpenInformation ? v.dot(previous)
                               : (v.dot(b) + prior * v.dot(previous)) / (lambda + prior));
  }
  return pos;
}

PoseEstimate Localise(const std::vector<Sighting>& sightings, const geometry::Pose2& previous,
                      const LearnedFrustum& frustum, const LocalisationOptions& options, int held,
                      int predicted_for) {
  const bool motion_known = predicted_for > 0;
  PoseEstimate out;
  out.pose = previous;
  std::vector<bool> use(sightings.size(), true);
  int suspect = -1;           // the wall left out on trial, in the last round
  PoseEstimate with_suspect;  // the pose with it, kept unless the trial shows it off
  for (int round = 0; round < 3; ++round) {
    out.end_moved = false;
    double s = 0.0, c = 0.0, heading_information = 0.0;
    int n = 0;
    for (size_t k = 0; k < sightings.size(); ++k) {
      if (!use[k]) continue;
      // Weighted by how well the wall's fit fixes its orientation: a short noisy wall (a door
      // jamb) must not turn the heading of walls metres long.
      const double w = OrientationWeight(*sightings[k].obs);
      const double d = sightings[k].world.alpha - sightings[k].obs->Alpha();
      s += w * std::sin(d), c += w * std::cos(d), ++n;
      // How far off the heading may be: the fit's sigma and a short piece's bias, which the
      // points' spread does not show (a 0.15 m jamb alone: headings 0.005-0.016 rad off, frame to
      // frame, against a fit's sigma of 0.003).
      const double sigma = std::hypot(1.0 / std::sqrt(w), PieceBlur(*sightings[k].obs));
      heading_information += 1.0 / (sigma * sigma);
    }
    if (n == 0) {
      // Every wall left out as an outlier of the first round's pose: that pose came from walls
      // that disagree by metres (a mis-registered wall), so it is not kept either.
      out.pose = previous;
      out.status = PoseStatus::kLost;
      out.planes = 0;
      return out;
    }
    const double yaw = std::atan2(s, c);
    out.yaw_sigma = 1.0 / std::sqrt(heading_information);
    const Matrix2d rot = Eigen::Rotation2Dd(yaw).toRotationMatrix();
    System sys;
    std::set<int64_t> planes;
    for (size_t k = 0; k < sightings.size(); ++k) {
      if (!use[k]) continue;
      const Sighting& x = sightings[k];
      if (x.world.known == Known::kAngle) continue;
      planes.insert(x.plane->Id());
      // The middle of the part in view lies on the wall's line: n . (c + R m) = n . P. Not
      // the offset d the fit gives at the foot of the perpendicular from the sensor: a fit's
      // offset is as good as its points only where they are, and a sliver of wall 2 m along
      // its line from that foot, 2 degrees off, put d 7 cm off.
      const Vector2d n = NormalOf(x.world.alpha);
      sys.Add(n, n.dot(x.world.point - rot * Middle(*x.obs)));
    }
    // A static edge seen now fixes the position along the wall (c + R e = P); used only where
    // the lines leave a direction open, as an edge taken for static may drift (occlusion). With
    // the motion known each end is weighed against the learnt velocity's prediction, as in the
    // motion model below: an end 2 m ahead at a grazing angle jumps by centimetres from frame to
    // frame, and one seen 5 cm short, taken alone, set the pose 5 cm back along a hallway, where
    // the groups made then kept it (hallway_out_and_back, σ = 1 cm, seed 164: ATE 0.050 m).
    Eigen::SelfAdjointEigenSolver<Matrix2d> line_eig(sys.a);
    bool ends_fix = false;
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
        const double w = motion_known ? EndWeight(frustum, *x.obs, e) : 1.0;
        sys.Add(t, t.dot(mapped - rot * x.obs->edge[e]), w);
        ends_fix = true;
      }
    }
    if (motion_known && ends_fix) {
      // The previous pose, fixed by such ends, is good to about a centimetre (0.5, 1 and 2 cm
      // gave the same on the runs traced), and the prediction drifts on from there.
      const Vector2d open = line_eig.eigenvectors().col(0);
      const double sigma =
          std::max(options.tracked_prediction, options.drift_rate * static_cast<double>(predicted_for));
      sys.AddPrior(open, open.dot(previous.Translation()),
                   std::pow(LearnedFrustum::kEdgeNoise / sigma, 2));
    }
    Eigen::SelfAdjointEigenSolver<Matrix2d> eig(sys.a);
    const double information = eig.eigenvalues()(0);
    const bool tracking = planes.size() >= 2 && information >= options.min_information;
    if (!tracking) {
      // §II.E motion model: a mapped wall end seen where the previous position predicts it.
      // Failing that, a wall end seen uncut from poses the walls fixed: a wall end stands still
      // (§II.C), so where it is seen now shows how far the sensor moved along the wall, as the
      // paper's growing partial plane does. Only the end the sensor samples finest: the spacing
      // of its rays along a wall grows as r^2 / h (r the end's distance, h the wall's), and a far
      // end seen at a glancing angle moves in steps of that spacing (0.1-0.3 m 3-5 m away down a
      // 2 m hallway, where one 2 m away is seen within 2 cm).
      const Vector2d open = eig.eigenvectors().col(0);
      bool finest = false;
      Vector2d finest_dir = Vector2d::Zero();
      double finest_along = 0.0, finest_spacing = std::numeric_limits<double>::infinity();
      int placed_ends = 0;
      for (size_t k = 0; k < sightings.size(); ++k) {
        const Sighting& x = sightings[k];
        if (!use[k] || x.world.known == Known::kAngle) continue;
        const Vector2d t = DirectionOf(x.world.alpha);
        for (int e = 0; e < 2; ++e) {
          Vector2d mapped;
          // Cut by the view (its bearing or its range) or seen past a nearer wall: no wall end.
          if (frustum.Clipped(x.obs->edge[e]) || x.obs->cut[e]) continue;
          const bool placed =
              x.world.known == Known::kPoint && EdgePoint(*x.plane, x.world, e, &mapped);
          if (!placed && !x.end_seen[e]) continue;
          const double along = t.dot((placed ? mapped : x.end[e]) - rot * x.obs->edge[e]);
          const double moved = along - t.dot(previous.Translation());
          if (placed) {
            if (std::abs(moved) >= options.end_gate) continue;
            // With the motion known the prediction is good to an end's noise and the velocity's
            // drift since the walls last fixed the position: an end further off is not the
            // wall's. The segmenter gave a wall's last 10 cm beside a door recess to a plane
            // across the corner for one iteration, one after a fixed pose, and the end left
            // moved the pose 7 cm back along the hallway for the 50 iterations of the motion
            // model after it (loop_other_sensor, σ = 1 cm, seed 13).
            const double drift = options.drift_rate * static_cast<double>(predicted_for);
            if (motion_known && std::abs(moved) >= LearnedFrustum::kEdgeNoise + drift) continue;
            // With the motion known, an end whose samples land further apart than its noise says
            // less than the learnt velocity: it stands for frames and jumps a column (one 4.8 m
            // ahead at a grazing angle, 12 cm columns: the pose stepped 4-9 cm frame to frame).
            const double spacing = frustum.EdgeSpacing(x.obs->edge[e], x.obs->d);
            if (motion_known && spacing > 2.0 * LearnedFrustum::kEdgeNoise) continue;
            sys.Add(t, along, motion_known ? EndWeight(frustum, *x.obs, e) : 1.0);
            placed_ends += motion_known ? 1 : 0;
            continue;
          }
          // Such an end is looked up only where no motion is known, so `previous` is the pose
          // held still, not a prediction: the sensor has since moved forwards by up to a step
          // (the platform drives forwards), never back. An end that puts it further back than
          // its noise is seen past where it stands (a corner's end 2 m ahead, seen 0.13 m past
          // the corner for an iteration): taken, it set the position back, and the gate about
          // that lagging position then turned away every end until the hallway's first door
          // frame, 0.26 m behind for 30 iterations. Forwards by up to a step for each iteration
          // held still as well: one end seen 9 cm short (a shrinking piece beside a recess)
          // held the start back, every honest end was then more than a step ahead, and the
          // first group was placed 0.3 m behind (hallway_out_and_back, σ = 1 cm, seed 11).
          const double forwards = t.dot(rot.col(0)) >= 0.0 ? moved : -moved;
          const double noise = LearnedFrustum::kEdgeNoise;
          const double reach = options.max_step * (1 + std::clamp(held, 0, options.max_held));
          if (forwards <= -noise || forwards >= reach + noise) continue;
          // Nor an end whose samples land further apart than its noise, as with the motion
          // known: the finest end in view may still be a coarse one. Turning on the spot at a
          // corner, ends 3-5 m down the next hallway (rays 0.24-0.33 m apart along the wall)
          // stepped the held position 5 and 8 cm forwards; a door jamb ahead was mapped from
          // there and its group placed 16 cm along the hallway, where the pose stayed for the
          // rest of the run (hallway_loop_doors, σ = 1 cm, seed 58).
          if (frustum.EdgeSpacing(x.obs->edge[e], x.obs->d) > 2.0 * noise) continue;
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
      // With the motion known, the ends weighed against the learnt velocity's prediction by
      // their noise: the prediction drifts by up to kDriftRate an iteration since the walls last
      // fixed the position, a mapped end is good to kEdgeNoise (the lines' unit weight stands
      // for that) and its samples' spacing along the wall combined. Taken alone, a pilaster face's
      // far end, mapped 3 cm short from sightings 2-5 m off, set the position 4 cm back on the
      // first iterations of a motion-model spell, and the end wall first seen from there was mapped
      // as far back (loop_other_sensor, σ = 1 cm, seed 14).
      if (placed_ends > 0) {
        const double sigma =
            std::max(options.drift_rate * static_cast<double>(predicted_for), options.drift_rate);
        const double w = std::pow(LearnedFrustum::kEdgeNoise / sigma, 2);
        sys.AddPrior(open, open.dot(previous.Translation()), w);
      }
      // The platform drives forwards (as the learnt velocity takes it): along an open direction
      // across the heading the position stays where it was, whatever an end seen at another
      // angle, off by its sampling, says (an office's door jamb moved it 1.3 cm a frame).
      const bool along_heading = std::abs(open.dot(rot.col(0))) >= options.along_heading;
      if (finest && along_heading) {
        sys.Add(finest_dir, finest_along);
        out.end_moved = true;
      }
    }
    // The previous position only decides a direction the walls leave open.
    const Vector2d pos = SolveWithPrior(sys.a, sys.b, previous.Translation(),
                                        options.prior_weight, options.min_information);
    out.pose = {pos.x(), pos.y(), yaw};
    out.planes = static_cast<int>(planes.size());
    out.position_information = sys.seen;
    out.status = tracking ? PoseStatus::kTracking : PoseStatus::kMotionModel;
    if (suspect >= 0) {
      // The trial without the worst-fitting wall: kept where the rest still fix the position,
      // agree among themselves, and put that wall off by more than a map's error.
      bool agree = tracking && std::abs(Residual(sightings[suspect], out.pose)) > options.misregistered;
      for (size_t k = 0; k < sightings.size() && agree; ++k) {
        if (use[k] && sightings[k].world.known != Known::kAngle) {
          agree = std::abs(Residual(sightings[k], out.pose)) < options.suspect;
        }
      }
      if (!agree) out = with_suspect;
      break;
    }
    // One round of outlier rejection: a mis-registered wall must not drag the pose.
    bool dropped = false;
    for (size_t k = 0; k < sightings.size() && round == 0; ++k) {
      const Sighting& x = sightings[k];
      if (!use[k] || x.world.known == Known::kAngle || sightings.size() < 3) continue;
      if (std::abs(Residual(x, out.pose)) > options.outlier) {
        use[k] = false;
        dropped = true;
      }
    }
    if (dropped) continue;
    // A wall registered as its neighbour a pilaster's depth away (0.3 m) drags a position that
    // three walls fix by a third of that, and no wall is then as far off as kOutlier: the
    // worst-fitting one is tried without. The face of a pilaster, seen tilted beside the wall it
    // stands out of while the sensor turned, took that wall's next sighting, and the pose went
    // 10 cm across the hallway for 70 iterations (loop_other_sensor, σ = 1 cm, seed 20).
    if (!tracking) break;
    int lines = 0;
    double worst = options.suspect;
    for (size_t k = 0; k < sightings.size(); ++k) {
      if (!use[k] || sightings[k].world.known == Known::kAngle) continue;
      ++lines;
      const double r = std::abs(Residual(sightings[k], out.pose));
      if (r > worst) worst = r, suspect = static_cast<int>(k);
    }
    if (suspect < 0 || lines < 3) break;
    with_suspect = out;
    use[suspect] = false;
  }
  return out;
}

}  // namespace relplane::mapper
