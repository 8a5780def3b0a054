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
  r.Read("corner_radius", &o.corner_radius);
  if (!(o.corner_radius >= 0.0)) r.Fail("corner_radius", "must be 0 (off) or positive");

  Reader reg = r.Child("registration");
  reg.Read("last_seen_window", &o.registration.last_seen_window);
  reg.Read("max_angle", &o.registration.max_angle);
  reg.Read("max_distance", &o.registration.max_distance);
  reg.Read("min_overlap", &o.registration.min_overlap);
  reg.Read("max_wall_normal_z", &o.registration.max_wall_normal_z);
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

  Reader grp = r.Child("grouping");
  grp.Read("min_observations", &o.grouping.min_observations);
  grp.Read("ungrouped_timeout", &o.grouping.ungrouped_timeout);
  grp.Read("min_common", &o.grouping.min_common);
  grp.Read("covisible_window", &o.grouping.covisible_window);
  grp.Read("recent_groups", &o.grouping.recent_groups);
  grp.Read("max_orientation_spread", &o.grouping.max_orientation_spread);
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
  if (o.comparison.min_samples < 2) cmp.Fail("min_samples", "must be at least 2");
  Positive(cmp, "static_std", o.comparison.static_std);

  Reader rg = r.Child("regrouping");
  rg.Read("enabled", &o.regrouping.enabled);
  rg.Read("reorder_after", &o.regrouping.reorder_after);
  rg.Read("regroup_after", &o.regrouping.regroup_after);
  rg.Read("min_interval", &o.regrouping.min_interval);
  rg.Read("freeze_after", &o.regrouping.freeze_after);
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
  Positive(loc, "prior_weight", o.localisation.prior_weight);
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
