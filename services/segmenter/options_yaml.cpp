#include "options_yaml.hpp"

namespace relplane::segmenter {
namespace {

using config::Reader;

template <class T>
void ReadPositive(Reader& r, const std::string& key, T* value) {
  r.Read(key, value);
  if (!(*value > 0)) r.Fail(key, "must be positive");
}

template <class T>
void ReadNonNegative(Reader& r, const std::string& key, T* value) {
  r.Read(key, value);
  if (*value < 0) r.Fail(key, "must not be negative");
}

}  // namespace

ServiceOptions ReadServiceOptions(Reader& r) {
  ServiceOptions s;
  Options& o = s.segmenter;
  ReadPositive(r, "sigma_min", &o.sigma_min);
  ReadPositive(r, "sigma_max", &o.sigma_max);
  if (o.sigma_max < o.sigma_min) r.Fail("sigma_max", "must be at least sigma_min");
  ReadPositive(r, "sigma_initial", &o.sigma_initial);
  ReadNonNegative(r, "range_noise", &o.range_noise);
  ReadPositive(r, "outlier_density", &o.outlier_density);
  ReadPositive(r, "em_points_min", &o.em_points_min);
  ReadPositive(r, "em_points_max", &o.em_points_max);
  ReadPositive(r, "em_fraction", &o.em_fraction);
  ReadPositive(r, "em_iterations", &o.em_iterations);
  ReadPositive(r, "max_rounds", &o.max_rounds);
  ReadPositive(r, "max_planes", &o.max_planes);
  ReadPositive(r, "converged_angle", &o.converged_angle);
  ReadPositive(r, "converged_offset", &o.converged_offset);
  ReadPositive(r, "proposal_trials", &o.proposal_trials);
  ReadPositive(r, "proposal_neighbours", &o.proposal_neighbours);
  if (o.proposal_neighbours < 8) r.Fail("proposal_neighbours", "must be at least 8");
  ReadPositive(r, "proposal_radius", &o.proposal_radius);
  ReadPositive(r, "proposal_max_rms", &o.proposal_max_rms);
  ReadPositive(r, "max_proposals_per_round", &o.max_proposals_per_round);
  ReadPositive(r, "merge_angle_deg", &o.merge_angle_deg);
  ReadPositive(r, "merge_distance", &o.merge_distance);
  ReadNonNegative(r, "piece_merge_angle_deg", &o.piece_merge_angle_deg);
  ReadNonNegative(r, "overlap_merge_angle_deg", &o.overlap_merge_angle_deg);
  ReadPositive(r, "min_em_points", &o.min_em_points);
  ReadPositive(r, "inlier_sigmas", &o.inlier_sigmas);
  ReadPositive(r, "min_points", &o.min_points);
  ReadPositive(r, "cell_size", &o.cell_size);
  ReadPositive(r, "cell_reach", &o.cell_reach);
  ReadNonNegative(r, "reach_spacings", &o.reach_spacings);
  ReadPositive(r, "max_reach", &o.max_reach);
  ReadPositive(r, "max_cells", &o.max_cells);
  ReadPositive(r, "fit_points_max", &o.fit_points_max);
  ReadNonNegative(r, "describe_points_max", &o.describe_points_max);
  ReadPositive(r, "vertical_max_nz", &o.vertical_max_nz);
  r.Read("ray_noise_fit", &o.ray_noise_fit);
  r.Read("dominant_line_fit", &o.dominant_line_fit);
  r.Read("wall_end_estimate", &o.wall_end_estimate);
  r.Read("drop_pieceless_planes", &o.drop_pieceless_planes);
  r.Read("seed", &o.seed);
  // The depth camera by name: its presets (relplane/common/depth_camera.hpp).
  std::string sensor;
  r.Read("sensor", &sensor);
  if (!sensor.empty() && !o.sensor.SetPreset(sensor)) {
    std::string names;
    for (const auto& n : camera::PresetNames()) names += (names.empty() ? "" : ", ") + n;
    r.Fail("sensor", "unknown sensor '" + sensor + "' (" + names + ")");
  }
  ReadPositive(r, "layer_rms_share", &o.sensor.layer_rms_share);
  ReadPositive(r, "surface_sigma_max", &o.sensor.surface_sigma_max);
  long max_points = static_cast<long>(s.max_points);
  ReadPositive(r, "max_points", &max_points);
  s.max_points = max_points;
  return s;
}

ServiceOptions LoadServiceOptions(const std::string& file) {
  if (file.empty()) return ServiceOptions{};
  Reader r = Reader::Load(file, "segmenter");
  ServiceOptions s = ReadServiceOptions(r);
  r.Finish();
  return s;
}

}  // namespace relplane::segmenter
