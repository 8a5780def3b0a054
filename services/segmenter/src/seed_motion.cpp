#include "seed_motion.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <utility>

namespace relplane::segmenter {
namespace {

// The sensor's motion between two frames as it moves a plane: p' = R p + t, so n' = R n and
// d' = d - n' . t.
struct Motion {
  Eigen::Matrix3f rotation = Eigen::Matrix3f::Identity();
  Eigen::Vector3f translation = Eigen::Vector3f::Zero();

  EmPlane Move(const EmPlane& p) const {
    EmPlane moved = p;
    moved.normal = rotation * p.normal;
    moved.centroid = rotation * p.centroid + translation;
    moved.d = -moved.normal.dot(moved.centroid);
    return moved;
  }
};

// Every plane of a frame moves with the one sensor motion (a rigid scene): estimated from the
// seeds EM kept, weighted by support — the rotation that best turns their normals into the
// fitted ones (Wahba's problem, by SVD), then the translation from the offsets' change in least
// squares, damped so a direction no plane constrains stays unmoved. False when the kept
// normals are all parallel: the rotation about them is unknown.
bool EstimateMotion(const std::vector<EmPlane>& seeds, const std::vector<EmPlane>& fits,
                    float min_support, Motion* motion) {
  Eigen::Matrix3d b = Eigen::Matrix3d::Zero();
  for (size_t j = 0; j < seeds.size(); ++j) {
    if (fits[j].support < min_support) continue;
    b += fits[j].support * fits[j].normal.cast<double>() *
         seeds[j].normal.cast<double>().transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(b, Eigen::ComputeFullU | Eigen::ComputeFullV);
  constexpr double kMinSecondWeight = 0.05;  // of the first: two normals at least ~3 degrees apart
  if (svd.singularValues()(1) <= kMinSecondWeight * svd.singularValues()(0)) return false;
  Eigen::Matrix3d fix = Eigen::Matrix3d::Identity();
  fix(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  const Eigen::Matrix3d rotation = svd.matrixU() * fix * svd.matrixV().transpose();
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  double weight = 0.0;
  for (size_t j = 0; j < seeds.size(); ++j) {
    if (fits[j].support < min_support) continue;
    const Eigen::Vector3d n = rotation * seeds[j].normal.cast<double>();
    a += fits[j].support * n * n.transpose();
    rhs += fits[j].support * n * (static_cast<double>(seeds[j].d) - fits[j].d);
    weight += fits[j].support;
  }
  constexpr double kDamping = 1e-3;  // of the total weight
  a += kDamping * weight * Eigen::Matrix3d::Identity();
  motion->rotation = rotation.cast<float>();
  motion->translation = a.ldlt().solve(rhs).cast<float>();
  return true;
}

// Whether EM's fit of a seed is where the sensor's motion carries it (within the merge limits)
// with enough support to stay.
bool Follows(const Options& options, const EmPlane& predicted, const EmPlane& fit,
             float min_support) {
  const float cos_merge = std::cos(options.merge.angle_deg * static_cast<float>(M_PI) / 180.0f);
  return fit.support >= min_support && predicted.normal.dot(fit.normal) > cos_merge &&
         std::fabs(predicted.normal.dot(fit.centroid) + predicted.d) < options.merge.distance;
}

// A seed whose fit EM lost (support below pruning) lies, after a move, further from its points
// than its sigma lets EM reach (a wall 4.5 m ahead moves 9 cm under a 1.1 degree turn, 20
// sigma): such seeds are put back where the motion of the others carries them. Seeds EM kept are
// left alone, even off the predicted place: a depth camera's distortion bends a plane's fit by a
// few degrees from frame to frame. Returns the seeds put back: index, predicted place and the
// seed's support.
std::vector<std::pair<size_t, EmPlane>> ReanchorLostSeeds(const std::vector<EmPlane>& seeds,
                                                          const SeedOptions& options,
                                                          float min_support,
                                                          std::vector<EmPlane>* planes) {
  std::vector<std::pair<size_t, EmPlane>> moved;
  const bool any_lost = std::any_of(planes->begin(), planes->begin() + seeds.size(),
                                    [&](const EmPlane& p) { return p.support < min_support; });
  Motion motion;
  if (!any_lost || !EstimateMotion(seeds, *planes, min_support, &motion)) return moved;
  // Beyond normal motion between frames the fits the motion came from may have jumped to other
  // surfaces, and proposals are the safer start.
  const float max_turn = options.max_turn_deg * static_cast<float>(M_PI) / 180.0f;  // radians
  if (Eigen::AngleAxisf(motion.rotation).angle() > max_turn ||
      motion.translation.norm() > options.max_shift) {
    return moved;
  }
  for (size_t j = 0; j < seeds.size(); ++j) {
    if ((*planes)[j].support >= min_support) continue;  // tracked, or bent its own way
    EmPlane predicted = motion.Move(seeds[j]);
    // A seed that the motion hardly moves was within EM's reach: its points are gone.
    const float shift = std::fabs(seeds[j].normal.dot(predicted.centroid) + seeds[j].d);
    if (shift <= seeds[j].sigma) continue;
    (*planes)[j] = predicted;
    (*planes)[j].support = 0.0f;
    moved.emplace_back(j, predicted);  // the record keeps the seed's support
  }
  return moved;
}

}  // namespace

int CarryLostSeeds(const Cloud& sample, const Options& options, const std::vector<EmPlane>& seeds,
                   float min_support, std::vector<EmPlane>* planes, Responsibilities* resp) {
  const auto moved = ReanchorLostSeeds(seeds, options.seeds, min_support, planes);
  if (moved.empty()) return 0;
  RunEm(sample, options, options.em.iterations, planes, resp);
  int kept = 0;
  for (const auto& [j, predicted] : moved) {
    const float least = std::max(options.seeds.kept_support * predicted.support, min_support);
    if (Follows(options, predicted, (*planes)[j], least)) {
      ++kept;
    } else {
      (*planes)[j].support = 0.0f;
    }
  }
  return kept;
}

}  // namespace relplane::segmenter
