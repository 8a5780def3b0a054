#include "options_yaml.hpp"

#include <utility>

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

// Keys of the flat layout the section had before it was split by concern: a file that still
// uses one is told where it went instead of only that it is unknown.
constexpr std::pair<const char*, const char*> kMovedKeys[] = {
    {"sigma_min", "noise.sigma_min"},
    {"sigma_max", "noise.sigma_max"},
    {"sigma_initial", "noise.sigma_initial"},
    {"range_noise", "noise.range_noise"},
    {"outlier_density", "noise.outlier_density"},
    {"em_points_min", "em.points_min"},
    {"em_points_max", "em.points_max"},
    {"em_fraction", "em.fraction"},
    {"em_iterations", "em.iterations"},
    {"max_rounds", "em.max_rounds"},
    {"max_planes", "em.max_planes"},
    {"converged_angle", "em.converged_angle"},
    {"converged_offset", "em.converged_offset"},
    {"min_em_points", "em.min_support"},
    {"proposal_trials", "proposals.trials"},
    {"proposal_neighbours", "proposals.neighbours"},
    {"proposal_radius", "proposals.radius"},
    {"proposal_max_rms", "proposals.max_rms"},
    {"max_proposals_per_round", "proposals.max_per_round"},
    {"merge_angle_deg", "merge.angle_deg"},
    {"merge_distance", "merge.distance"},
    {"piece_merge_angle_deg", "merge.piece_angle_deg"},
    {"overlap_merge_angle_deg", "merge.overlap_angle_deg"},
    {"inlier_sigmas", "assignment.inlier_sigmas"},
    {"min_points", "extents.min_points"},
    {"cell_size", "extents.cell_size"},
    {"cell_reach", "extents.cell_reach"},
    {"reach_spacings", "extents.reach_spacings"},
    {"max_reach", "extents.max_reach"},
    {"max_cells", "extents.max_cells"},
    {"vertical_max_nz", "extents.vertical_max_nz"},
    {"describe_points_max", "description.points_max"},
    {"fit_points_max", "description.fit_points_max"},
};

// Options that are no longer options: the segmenter always does what they switched on.
constexpr const char* kSettledKeys[] = {"wall_end_estimate", "ray_noise_fit", "dominant_line_fit",
                                        "drop_pieceless_planes"};

void RejectOldKeys(const Reader& r) {
  for (const auto& [old_key, new_key] : kMovedKeys) {
    if (r.Has(old_key)) r.Fail(old_key, std::string("moved to '") + new_key + "'");
  }
  for (const char* key : kSettledKeys) {
    if (r.Has(key)) r.Fail(key, "no longer an option: always on");
  }
}

void ReadNoise(Reader r, NoiseOptions* o) {
  ReadPositive(r, "sigma_min", &o->sigma_min);
  ReadPositive(r, "sigma_max", &o->sigma_max);
  if (o->sigma_max < o->sigma_min) r.Fail("sigma_max", "must be at least sigma_min");
  ReadPositive(r, "sigma_initial", &o->sigma_initial);
  ReadNonNegative(r, "range_noise", &o->range_noise);
  ReadPositive(r, "outlier_density", &o->outlier_density);
}

void ReadEm(Reader r, EmOptions* o) {
  ReadPositive(r, "points_min", &o->points_min);
  ReadPositive(r, "points_max", &o->points_max);
  ReadPositive(r, "fraction", &o->fraction);
  ReadPositive(r, "iterations", &o->iterations);
  ReadPositive(r, "max_rounds", &o->max_rounds);
  ReadPositive(r, "max_planes", &o->max_planes);
  ReadPositive(r, "converged_angle", &o->converged_angle);
  ReadPositive(r, "converged_offset", &o->converged_offset);
  ReadPositive(r, "min_support", &o->min_support);
}

void ReadProposals(Reader r, ProposalOptions* o) {
  ReadPositive(r, "trials", &o->trials);
  ReadPositive(r, "neighbours", &o->neighbours);
  ReadPositive(r, "radius", &o->radius);
  ReadPositive(r, "max_rms", &o->max_rms);
  ReadPositive(r, "max_per_round", &o->max_per_round);
  ReadPositive(r, "min_neighbours", &o->min_neighbours);
  if (o->neighbours < o->min_neighbours) r.Fail("neighbours", "must be at least min_neighbours");
  ReadPositive(r, "max_flatness", &o->max_flatness);
  if (o->max_flatness > 1.0) r.Fail("max_flatness", "must be at most 1");
  ReadPositive(r, "inlier_sigmas", &o->inlier_sigmas);
}

void ReadMerge(Reader r, MergeOptions* o) {
  ReadPositive(r, "angle_deg", &o->angle_deg);
  ReadPositive(r, "distance", &o->distance);
  ReadNonNegative(r, "piece_angle_deg", &o->piece_angle_deg);
  ReadNonNegative(r, "overlap_angle_deg", &o->overlap_angle_deg);
}

void ReadSeeds(Reader r, SeedOptions* o) {
  ReadPositive(r, "kept_support", &o->kept_support);
  ReadPositive(r, "max_turn_deg", &o->max_turn_deg);
  ReadPositive(r, "max_shift", &o->max_shift);
}

void ReadExtents(Reader r, ExtentOptions* o) {
  ReadPositive(r, "min_points", &o->min_points);
  ReadPositive(r, "cell_size", &o->cell_size);
  ReadPositive(r, "cell_reach", &o->cell_reach);
  ReadNonNegative(r, "reach_spacings", &o->reach_spacings);
  ReadPositive(r, "max_reach", &o->max_reach);
  ReadPositive(r, "max_cells", &o->max_cells);
  ReadPositive(r, "vertical_max_nz", &o->vertical_max_nz);
  ReadPositive(r, "trim_sigmas", &o->trim_sigmas);
  ReadNonNegative(r, "max_refits", &o->max_refits);
  ReadPositive(r, "max_end_spacing", &o->max_end_spacing);
  ReadPositive(r, "range_cut_share", &o->range_cut_share);
  if (o->range_cut_share > 1.0f) r.Fail("range_cut_share", "must be at most 1");
}

void ReadDescription(Reader r, DescriptionOptions* o) {
  ReadNonNegative(r, "points_max", &o->points_max);
  ReadPositive(r, "fit_points_max", &o->fit_points_max);
  ReadPositive(r, "leaning_rms", &o->leaning_rms);
  ReadPositive(r, "min_line_share", &o->min_line_share);
  if (o->min_line_share > 1.0) r.Fail("min_line_share", "must be at most 1");
  ReadNonNegative(r, "min_noise_points", &o->min_noise_points);
}

}  // namespace

ServiceOptions ReadServiceOptions(Reader& r) {
  RejectOldKeys(r);
  ServiceOptions s;
  Options& o = s.segmenter;
  ReadNoise(r.Child("noise"), &o.noise);
  ReadEm(r.Child("em"), &o.em);
  ReadProposals(r.Child("proposals"), &o.proposals);
  ReadMerge(r.Child("merge"), &o.merge);
  ReadSeeds(r.Child("seeds"), &o.seeds);
  Reader assignment = r.Child("assignment");
  ReadPositive(assignment, "inlier_sigmas", &o.assignment.inlier_sigmas);
  ReadPositive(assignment, "crossing_angle_deg", &o.assignment.crossing_angle_deg);
  ReadExtents(r.Child("extents"), &o.extents);
  ReadDescription(r.Child("description"), &o.description);
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
  ReadPositive(r, "grazing_margin_deg", &o.sensor.grazing_margin_deg);
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
