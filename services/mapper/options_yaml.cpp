#include "options_yaml.hpp"

namespace relplane::mapper {
namespace {

using config::Reader;

void Positive(Reader& r, const std::string& key, double value) {
  if (!(value > 0.0)) r.Fail(key, "must be positive");
}

}  // namespace

MapperOptions ReadMapperOptions(Reader& r) {
  MapperOptions o;
  Reader start = r.Child("start_pose");
  start.Read("x", &o.start_pose.x);
  start.Read("y", &o.start_pose.y);
  start.Read("z", &o.start_pose.z);
  start.Read("yaw", &o.start_pose.yaw);
  r.Read("max_observations", &o.max_observations);
  if (o.max_observations < 16) r.Fail("max_observations", "must be at least 16");

  Reader fit = r.Child("fit");
  fit.Read("orientation_floor", &o.fit.orientation_floor);
  fit.Read("piece_blur", &o.fit.piece_blur);
  Positive(fit, "orientation_floor", o.fit.orientation_floor);
  Positive(fit, "piece_blur", o.fit.piece_blur);

  Reader rp = r.Child("rltplane");
  rp.Read("noise_hysteresis", &o.rltplane.noise_hysteresis);
  rp.Read("smoothing", &o.rltplane.smoothing);
  rp.Read("noise_window", &o.rltplane.noise_window);
  rp.Read("full_length_sightings", &o.rltplane.full_length_sightings);
  rp.Read("retired_lengths", &o.rltplane.retired_lengths);
  if (!(o.rltplane.noise_hysteresis >= 0.0)) rp.Fail("noise_hysteresis", "must be 0 or more");
  if (o.rltplane.smoothing < 3) rp.Fail("smoothing", "must be at least 3");
  if (o.rltplane.noise_window < 1) rp.Fail("noise_window", "must be at least 1");
  if (o.rltplane.full_length_sightings < 1) rp.Fail("full_length_sightings", "must be at least 1");
  if (o.rltplane.retired_lengths < 2) rp.Fail("retired_lengths", "must be at least 2");

  Reader view = r.Child("view");
  view.Read("bearing_margin", &o.view.bearing_margin);
  view.Read("min_pile", &o.view.min_pile);
  view.Read("pile_contrast", &o.view.pile_contrast);
  view.Read("pile_beyond_ratio", &o.view.pile_beyond_ratio);
  view.Read("min_support", &o.view.min_support);
  view.Read("min_walls", &o.view.min_walls);
  if (!(o.view.bearing_margin >= 0.0)) view.Fail("bearing_margin", "must be 0 or more");
  if (o.view.min_pile < 1) view.Fail("min_pile", "must be at least 1");
  Positive(view, "pile_contrast", o.view.pile_contrast);
  if (o.view.pile_beyond_ratio < 1) view.Fail("pile_beyond_ratio", "must be at least 1");
  if (o.view.min_support < 1) view.Fail("min_support", "must be at least 1");
  if (o.view.min_walls < 1) view.Fail("min_walls", "must be at least 1");

  Reader reg = r.Child("registration");
  reg.Read("last_seen_window", &o.registration.last_seen_window);
  reg.Read("max_angle", &o.registration.max_angle);
  reg.Read("max_distance", &o.registration.max_distance);
  reg.Read("min_overlap", &o.registration.min_overlap);
  reg.Read("max_wall_normal_z", &o.registration.max_wall_normal_z);
  reg.Read("end_jump", &o.registration.end_jump);
  reg.Read("end_memory", &o.registration.end_memory);
  reg.Read("same_surface", &o.registration.same_surface);
  reg.Read("occlusion_bearing", &o.registration.occlusion_bearing);
  reg.Read("occlusion_nearer", &o.registration.occlusion_nearer);
  if (o.registration.last_seen_window < 1) reg.Fail("last_seen_window", "must be at least 1");
  Positive(reg, "max_angle", o.registration.max_angle);
  Positive(reg, "max_distance", o.registration.max_distance);

  Reader back = r.Child("backtrack");
  back.Read("enabled", &o.backtrack.enabled);
  back.Read("max_angle", &o.backtrack.max_angle);
  back.Read("max_distance", &o.backtrack.max_distance);
  back.Read("margin", &o.backtrack.margin);
  back.Read("open_margin", &o.backtrack.open_margin);
  back.Read("min_overlap", &o.backtrack.min_overlap);
  back.Read("line_max_angle", &o.backtrack.line_max_angle);
  back.Read("same_surface", &o.backtrack.same_surface);

  Reader grp = r.Child("grouping");
  grp.Read("min_observations", &o.grouping.min_observations);
  grp.Read("ungrouped_timeout", &o.grouping.ungrouped_timeout);
  grp.Read("min_common", &o.grouping.min_common);
  grp.Read("covisible_window", &o.grouping.covisible_window);
  grp.Read("recent_groups", &o.grouping.recent_groups);
  grp.Read("max_orientation_spread", &o.grouping.max_orientation_spread);
  grp.Read("min_common_orientation", &o.grouping.min_common_orientation);
  if (o.grouping.min_observations < 1) grp.Fail("min_observations", "must be at least 1");
  if (o.grouping.recent_groups < 1) grp.Fail("recent_groups", "must be at least 1");
  if (!(o.grouping.max_orientation_spread > 0.0)) {
    grp.Fail("max_orientation_spread", "must be positive");
  }

  Reader cmp = r.Child("comparison");
  cmp.Read("min_samples", &o.comparison.min_samples);
  cmp.Read("static_std", &o.comparison.static_std);
  cmp.Read("static_floor", &o.comparison.static_floor);
  cmp.Read("static_ratio", &o.comparison.static_ratio);
  cmp.Read("phase_hysteresis", &o.comparison.phase_hysteresis);
  cmp.Read("parallel_angle", &o.comparison.parallel_angle);
  cmp.Read("max_subinterval", &o.comparison.max_subinterval);
  cmp.Read("freeze_lag", &o.comparison.freeze_lag);
  cmp.Read("min_motion", &o.comparison.min_motion);
  cmp.Read("uncut_share", &o.comparison.uncut_share);
  cmp.Read("spread_scale", &o.comparison.spread_scale);
  cmp.Read("parallel_sin", &o.comparison.parallel_sin);
  cmp.Read("pooled_std", &o.comparison.pooled_std);
  cmp.Read("edge_along_std", &o.comparison.edge_along_std);
  if (o.comparison.min_samples < 2) cmp.Fail("min_samples", "must be at least 2");
  Positive(cmp, "static_std", o.comparison.static_std);
  Positive(cmp, "spread_scale", o.comparison.spread_scale);
  Positive(cmp, "pooled_std", o.comparison.pooled_std);
  Positive(cmp, "edge_along_std", o.comparison.edge_along_std);
  if (!(o.comparison.parallel_sin > 0.0 && o.comparison.parallel_sin < 1.0)) {
    cmp.Fail("parallel_sin", "must be between 0 and 1");
  }

  Reader gm = r.Child("global_map");
  gm.Read("end_still", &o.global_map.end_still);
  gm.Read("first_end_agreement", &o.global_map.first_end_agreement);
  gm.Read("line_agreement", &o.global_map.line_agreement);
  gm.Read("pose_noise", &o.global_map.pose_noise);
  gm.Read("spans_open", &o.global_map.spans_open);
  gm.Read("line_noise", &o.global_map.line_noise);
  gm.Read("full_line", &o.global_map.full_line);
  gm.Read("edge_gate", &o.global_map.edge_gate);
  gm.Read("chained_orientation_prior", &o.global_map.chained_orientation_prior);
  Positive(gm, "end_still", o.global_map.end_still);
  Positive(gm, "first_end_agreement", o.global_map.first_end_agreement);
  Positive(gm, "line_agreement", o.global_map.line_agreement);
  Positive(gm, "pose_noise", o.global_map.pose_noise);
  Positive(gm, "line_noise", o.global_map.line_noise);
  Positive(gm, "full_line", o.global_map.full_line);
  Positive(gm, "edge_gate", o.global_map.edge_gate);
  Positive(gm, "chained_orientation_prior", o.global_map.chained_orientation_prior);
  if (!(o.global_map.spans_open > 0.0 && o.global_map.spans_open <= 1.0)) {
    gm.Fail("spans_open", "must be in (0, 1]");
  }

  Reader rg = r.Child("regrouping");
  rg.Read("enabled", &o.regrouping.enabled);
  rg.Read("reorder_after", &o.regrouping.reorder_after);
  rg.Read("regroup_after", &o.regrouping.regroup_after);
  rg.Read("min_interval", &o.regrouping.min_interval);
  rg.Read("freeze_after", &o.regrouping.freeze_after);
  rg.Read("sweep_period", &o.regrouping.sweep_period);
  if (o.regrouping.sweep_period < 1) rg.Fail("sweep_period", "must be at least 1");
  if (o.regrouping.reorder_after < 1) rg.Fail("reorder_after", "must be at least 1");
  if (o.regrouping.regroup_after <= o.regrouping.reorder_after) {
    rg.Fail("regroup_after", "must be after reorder_after");
  }
  if (o.regrouping.freeze_after <= o.regrouping.regroup_after) {
    rg.Fail("freeze_after", "must be after regroup_after");
  }

  Reader loc = r.Child("localisation");
  loc.Read("min_information", &o.localisation.min_information);
  loc.Read("prior_weight", &o.localisation.prior_weight);
  loc.Read("outlier", &o.localisation.outlier);
  loc.Read("suspect", &o.localisation.suspect);
  loc.Read("misregistered", &o.localisation.misregistered);
  loc.Read("drift_rate", &o.localisation.drift_rate);
  loc.Read("tracked_prediction", &o.localisation.tracked_prediction);
  loc.Read("end_gate", &o.localisation.end_gate);
  loc.Read("along_heading", &o.localisation.along_heading);
  loc.Read("max_step", &o.localisation.max_step);
  loc.Read("max_held", &o.localisation.max_held);
  loc.Read("open_information", &o.localisation.open_information);
  loc.Read("edge_noise", &o.localisation.edge_noise);
  loc.Read("heading_gate", &o.localisation.heading_gate);
  Positive(loc, "prior_weight", o.localisation.prior_weight);
  Positive(loc, "drift_rate", o.localisation.drift_rate);
  Positive(loc, "tracked_prediction", o.localisation.tracked_prediction);
  Positive(loc, "max_step", o.localisation.max_step);
  Positive(loc, "open_information", o.localisation.open_information);
  Positive(loc, "edge_noise", o.localisation.edge_noise);
  Positive(loc, "heading_gate", o.localisation.heading_gate);

  Reader mo = r.Child("motion");
  mo.Read("turn_rate", &o.motion.turn_rate);
  mo.Read("window", &o.motion.window);
  mo.Read("min_span", &o.motion.min_span);
  mo.Read("max_gap", &o.motion.max_gap);
  mo.Read("max_stretches", &o.motion.max_stretches);
  mo.Read("max_coast", &o.motion.max_coast);
  mo.Read("pose_history", &o.motion.pose_history);
  mo.Read("odometry_drift", &o.motion.odometry_drift);
  mo.Read("odometry_scale_span", &o.motion.odometry_scale_span);
  Positive(mo, "turn_rate", o.motion.turn_rate);
  if (!(o.motion.odometry_drift >= 0.0)) mo.Fail("odometry_drift", "must be 0 or more");
  if (!(o.motion.odometry_scale_span > 0.0)) mo.Fail("odometry_scale_span", "must be over 0");
  if (o.motion.min_span < 1) mo.Fail("min_span", "must be at least 1");
  if (o.motion.max_stretches < 1) mo.Fail("max_stretches", "must be at least 1");
  if (o.motion.pose_history < o.motion.max_gap + o.motion.window) {
    mo.Fail("pose_history", "must cover max_gap + window");
  }

  Reader gr = r.Child("graph");
  gr.Read("enabled", &o.graph.enabled);
  gr.Read("angle_sigma", &o.graph.angle_sigma);
  gr.Read("position_sigma", &o.graph.position_sigma);
  gr.Read("prior_sigma", &o.graph.prior_sigma);
  gr.Read("pose_tie_sigma", &o.graph.pose_tie_sigma);
  gr.Read("pose_tie_angle_sigma", &o.graph.pose_tie_angle_sigma);
  gr.Read("max_iterations", &o.graph.max_iterations);
  gr.Read("robust", &o.graph.robust);
  gr.Read("consistent", &o.graph.consistent);
  gr.Read("initial_damping", &o.graph.initial_damping);
  gr.Read("tie_min_jump", &o.graph.tie_min_jump);
  gr.Read("tie_min_turn", &o.graph.tie_min_turn);
  gr.Read("max_pose_ties", &o.graph.max_pose_ties);
  Positive(gr, "angle_sigma", o.graph.angle_sigma);
  Positive(gr, "position_sigma", o.graph.position_sigma);
  Positive(gr, "prior_sigma", o.graph.prior_sigma);
  Positive(gr, "pose_tie_sigma", o.graph.pose_tie_sigma);
  Positive(gr, "pose_tie_angle_sigma", o.graph.pose_tie_angle_sigma);
  Positive(gr, "robust", o.graph.robust);
  Positive(gr, "consistent", o.graph.consistent);
  if (o.graph.max_iterations < 1) gr.Fail("max_iterations", "must be at least 1");
  if (o.graph.max_pose_ties < 1) gr.Fail("max_pose_ties", "must be at least 1");

  Reader pm = r.Child("published_map");
  pm.Read("corner_radius", &o.published_map.corner_radius);
  pm.Read("merge_angle", &o.published_map.merge_angle);
  pm.Read("merge_distance", &o.published_map.merge_distance);
  pm.Read("cut_overlap", &o.published_map.cut_overlap);
  pm.Read("min_shortened_radii", &o.published_map.min_shortened_radii);
  pm.Read("max_shortened_fraction", &o.published_map.max_shortened_fraction);
  pm.Read("min_corner_angle", &o.published_map.min_corner_angle);
  if (!(o.published_map.corner_radius >= 0.0)) {
    pm.Fail("corner_radius", "must be 0 (off) or positive");
  }
  Positive(pm, "merge_distance", o.published_map.merge_distance);
  return o;
}

MapperOptions LoadMapperOptions(const std::string& file) {
  if (file.empty()) return {};
  Reader r = Reader::Load(file, "mapper");
  MapperOptions o = ReadMapperOptions(r);
  r.Finish();
  return o;
}

}  // namespace relplane::mapper
