#pragma once
// The Relative Plane mapper (the paper, §II): one call per iteration with the untransformed
// planes of that iteration; reads as register -> group -> compare -> build maps -> localise.

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "relplane/mapper/localisation.hpp"
#include "relplane/mapper/observation.hpp"
#include "relplane/mapper/odometry.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/state.hpp"

namespace relplane::mapper {

// A mapped wall in the world frame (what MAP carries).
struct MappedPlane {
  int64_t id = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double d = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> vertices;  // the wall's rectangle, ends at its edges
  int64_t observations = 0;
  bool both_ends_known = false;
  bool end_known[2] = {false, false};  // vertices[0] (lo) and vertices[1] (hi) are wall ends
};

struct MappedGroup {
  int64_t id = 0;
  int64_t basis = 0;
  std::vector<int64_t> members;
};

struct MapSnapshot {
  std::vector<MappedPlane> planes;
  std::vector<MappedGroup> groups;
};

// §II.C: an edge cut by the view is never a static edge, and the view is learnt as the sensor
// reports (LearnedFrustum). Marks the stored edges `frustum` now finds cut that were judged
// uncut before it knew its range limit, with the sightings kept from them (a plane's first,
// a group's when made and from fixed poses), and has the groups holding them built again.
// Returns how many edges it marked.
int MarkViewCuts(const LearnedFrustum& frustum, MapperState& state);

class Mapper {
 public:
  explicit Mapper(MapperOptions options = {});

  // Processes one plane set; `iteration` must increase (gaps are fine). Returns the pose.
  PoseEstimate Process(int64_t iteration, const std::vector<PlaneInput>& planes);
  // The same with wheel odometry's motion since the previous plane set, when ODOMETRY is on
  // the bus (odometry.hpp). The algorithm does not take it yet: the pose is the planes' alone.
  PoseEstimate Process(int64_t iteration, const std::vector<PlaneInput>& planes,
                       const std::optional<OdometryIncrement>& /*odometry*/) {
    return Process(iteration, planes);
  }

  // True when the map changed since the last call to TakeMapChanged().
  bool TakeMapChanged();
  MapSnapshot Map() const;
  const MapperState& State() const { return state_; }
  const MapperOptions& Options() const { return options_; }
  // Sensor height added to planes' z (the start pose's z).
  double Height() const { return options_.start_pose.z; }

 private:
  std::vector<int64_t> Register(int64_t iteration, std::vector<Observation>& observations);
  // A loop closing (§II.A end): walls of group `oldest` matched again while `chain`, the walls in
  // view registered as usual, put the sensor at `pose`. Noted for MakePoseTie when all of
  // `chain` was placed by groups well after `oldest`.
  void NoteClosing(const std::vector<Sighting>& chain, const geometry::Pose2& pose, int64_t oldest);
  // The PoseTie of a loop noted closing at this iteration, from the pose `estimate` found.
  void MakePoseTie(const PoseEstimate& estimate);
  void Compare(int64_t iteration, const std::vector<int64_t>& visible);
  void BuildMaps();
  PoseEstimate Localise(int64_t iteration, const std::vector<int64_t>& visible);
  // `known`: whether the motion is known: a velocity learnt from a stretch of motion (not a
  // turn on the spot), or turning on the spot now (standing still).
  geometry::Pose2 Predict(int64_t iteration, bool* known) const;

  MapperOptions options_;
  MapperState state_;
  geometry::Pose2 pose_;
  geometry::Pose2 predicted_;  // pose_ moved on at the learnt velocity to this iteration
  bool motion_known_ = false;  // Predict's `known` for this iteration
  int64_t last_walled_ = -1;   // the last iteration whose pose mapped walls placed
  // Iterations in a row whose position was held still: no motion known, the walls leaving the
  // heading open and no wall end moving it (Localise's `held`).
  int held_ = 0;
  LearnedFrustum frustum_;
  // The frustum's range limit the stored edges were last judged against (MarkViewCuts).
  double judged_range_limit_ = std::numeric_limits<double>::infinity();
  int64_t last_iteration_ = -1;
  int64_t previous_iteration_ = -1;  // the iteration before last_iteration_
  // A loop closing at this iteration (Register): the pose from the chain's walls alone and the
  // groups of the two sides, made a PoseTie once the iteration's pose is known.
  bool closing_ = false;
  geometry::Pose2 closing_pose_;
  int64_t closing_from_ = -1;  // the chain's newest group among the walls in view
  int64_t closing_to_ = -1;    // the oldest group among the re-seen walls
  bool closing_open_ = false;  // the chain's walls left the direction closing_open_alpha_ open
  double closing_open_alpha_ = 0.0;
};

}  // namespace relplane::mapper
