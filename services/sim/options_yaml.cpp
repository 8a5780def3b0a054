#include "options_yaml.hpp"

#include <cmath>
#include <stdexcept>

namespace relplane::sim {

namespace {

using config::Reader;

template <int N>
void ReadVector(Reader& r, const std::string& key, Eigen::Matrix<double, N, 1>* out) {
  if (!r.Has(key)) return;
  std::vector<double> values;
  r.Read(key, &values);
  if (values.size() != N) r.Fail(key, "expected a list of " + std::to_string(N) + " numbers");
  for (int i = 0; i < N; ++i) (*out)[i] = values[i];
}

void RequirePositive(Reader& r, const std::string& key, double value) {
  if (!(value > 0.0)) r.Fail(key, "must be positive");
}

void RequireNonNegative(Reader& r, const std::string& key, double value) {
  if (!(value >= 0.0)) r.Fail(key, "must not be negative");
}

GeneratorSpec ReadGenerator(Reader& r) {
  std::string type;
  r.ReadRequired("type", &type);
  if (type == "straight_hallway") {
    StraightHallwayParams p;
    r.Read("length", &p.length);
    r.Read("width", &p.width);
    r.Read("start", &p.start);
    r.Read("closed_ends", &p.closed_ends);
    RequirePositive(r, "length", p.length);
    RequirePositive(r, "width", p.width);
    return p;
  }
  if (type == "hallway_loop") {
    HallwayLoopParams p;
    ReadVector(r, "size", &p.size);
    r.Read("width", &p.width);
    r.Read("recess_spacing", &p.recess_spacing);
    r.Read("recess_width", &p.recess_width);
    r.Read("recess_depth", &p.recess_depth);
    RequirePositive(r, "width", p.width);
    if (!(p.size.minCoeff() > 2.0 * p.width)) r.Fail("size", "must exceed twice the width");
    RequireNonNegative(r, "recess_spacing", p.recess_spacing);
    RequirePositive(r, "recess_width", p.recess_width);
    RequirePositive(r, "recess_depth", p.recess_depth);
    if (p.recess_spacing > 0.0 && !(p.recess_width < p.recess_spacing)) {
      r.Fail("recess_width", "must be less than recess_spacing, or recesses would merge");
    }
    return p;
  }
  if (type == "office") {
    OfficeParams p;
    std::vector<double> rooms;
    if (r.Has("rooms")) {
      r.Read("rooms", &rooms);
      if (rooms.size() != 2 || rooms[0] < 1 || rooms[1] < 1 || rooms[0] != std::floor(rooms[0]) ||
          rooms[1] != std::floor(rooms[1])) {
        r.Fail("rooms", "expected two whole numbers of rooms, each at least 1");
      }
      p.rooms = Eigen::Vector2i(static_cast<int>(rooms[0]), static_cast<int>(rooms[1]));
    }
    ReadVector(r, "room_size", &p.room_size);
    r.Read("door_width", &p.door_width);
    r.Read("door_height", &p.door_height);
    r.Read("frame_depth", &p.frame_depth);
    if (!(p.room_size.minCoeff() > 0.0)) r.Fail("room_size", "must be positive");
    RequirePositive(r, "door_width", p.door_width);
    if (!(p.door_width < p.room_size.minCoeff())) {
      r.Fail("door_width", "must be narrower than the rooms");
    }
    RequirePositive(r, "door_height", p.door_height);
    RequireNonNegative(r, "frame_depth", p.frame_depth);
    return p;
  }
  if (type == "random_indoor") {
    RandomIndoorParams p;
    long long seed = static_cast<long long>(p.seed);
    r.Read("seed", &seed);
    if (seed < 0) r.Fail("seed", "must not be negative");
    p.seed = static_cast<uint64_t>(seed);
    return p;
  }
  r.Fail("type", "unknown generator '" + type +
                     "' (straight_hallway, hallway_loop, office, random_indoor)");
}

void ReadWorld(Reader r, WorldOptions* w) {
  r.Read("height", &w->height);
  RequirePositive(r, "height", w->height);
  r.Read("floor", &w->floor);
  r.Read("ceiling", &w->ceiling);
  // Any explicit content replaces the default world.
  if (r.Has("generators") || r.Has("walls") || r.Has("rectangles")) w->generators.clear();
  for (Reader& g : r.Children("generators")) w->generators.push_back(ReadGenerator(g));
  for (Reader& s : r.Children("walls")) {
    WallSpec wall;
    if (!s.Has("from")) s.Fail("from", "missing required key");
    if (!s.Has("to")) s.Fail("to", "missing required key");
    ReadVector(s, "from", &wall.from);
    ReadVector(s, "to", &wall.to);
    s.Read("base", &wall.base);
    s.Read("height", &wall.height);
    if ((wall.to - wall.from).norm() <= 0.0) s.Fail("to", "the wall has no length");
    if (s.Has("height")) RequirePositive(s, "height", wall.height);
    w->walls.push_back(wall);
  }
  for (Reader& s : r.Children("rectangles")) {
    Rect rect;
    for (const char* key : {"origin", "u", "v"}) {
      if (!s.Has(key)) s.Fail(key, "missing required key");
    }
    ReadVector(s, "origin", &rect.origin);
    ReadVector(s, "u", &rect.u);
    ReadVector(s, "v", &rect.v);
    if (rect.u.norm() <= 0.0) s.Fail("u", "must not be zero");
    if (rect.v.norm() <= 0.0) s.Fail("v", "must not be zero");
    if (std::abs(rect.u.dot(rect.v)) > 1e-9 * rect.u.norm() * rect.v.norm()) {
      s.Fail("v", "must be perpendicular to u");
    }
    w->rectangles.push_back(rect);
  }
  if (w->generators.empty() && w->walls.empty() && w->rectangles.empty()) {
    r.Fail("generators", "the world is empty: give generators, walls or rectangles");
  }
}

// A generated world comes with its route: the trajectory's defaults, which the scenario's own
// keys still override.
void RouteOfGeneratedWorld(Reader r, const WorldOptions& world, TrajectoryOptions* t) {
  const RandomIndoorParams* generated = nullptr;
  for (const GeneratorSpec& g : world.generators) {
    if (const auto* p = std::get_if<RandomIndoorParams>(&g)) {
      if (generated != nullptr) r.Fail("generators", "at most one random_indoor generator");
      generated = p;
    }
  }
  if (generated == nullptr) return;
  const IndoorLayout layout = MakeRandomIndoor(*generated);
  t->waypoints = layout.route;
  t->closed = layout.closed;
  t->laps = layout.laps;
  t->drive_back = layout.drive_back;
  t->turn = TurnMode::kInPlace;
}

void ReadTrajectory(Reader r, TrajectoryOptions* t) {
  if (r.Has("waypoints")) {
    t->waypoints.clear();
    for (Reader& p : r.Children("waypoints")) {
      Eigen::Vector2d q;
      p.ReadRequired("x", &q.x());
      p.ReadRequired("y", &q.y());
      t->waypoints.push_back(q);
    }
  }
  r.Read("speed", &t->speed);
  r.Read("turn_rate", &t->turn_rate);
  std::string turn = t->turn == TurnMode::kSmooth ? "smooth" : "in_place";
  r.Read("turn", &turn);
  if (turn == "in_place") {
    t->turn = TurnMode::kInPlace;
  } else if (turn == "smooth") {
    t->turn = TurnMode::kSmooth;
  } else {
    r.Fail("turn", "expected in_place or smooth");
  }
  r.Read("laps", &t->laps);
  r.Read("closed", &t->closed);
  r.Read("drive_back", &t->drive_back);
  RequirePositive(r, "speed", t->speed);
  RequirePositive(r, "turn_rate", t->turn_rate);
  if (t->laps < 1) r.Fail("laps", "must be at least 1");
  if (t->laps > 1 && !t->closed) r.Fail("laps", "more than one lap needs closed: true");
  try {
    Trajectory check(*t);
  } catch (const std::invalid_argument& e) {
    r.Fail("waypoints", e.what());
  }
}

// sim.sensor.model and the camera parameters a named model lets a scenario change.
void ReadCameraModel(Reader& r, SensorOptions* s) {
  std::string model = s->camera.name;
  r.Read("model", &model);
  const char* const kCameraKeys[] = {"baseline",  "focal_px",  "disparity_step",
                                     "lateral_px", "min_depth", "max_depth",
                                     "max_incidence_deg"};
  if (model == "gaussian") {
    s->camera = camera::DepthCameraModel{};
    for (const char* key : kCameraKeys) {
      if (r.Has(key)) r.Fail(key, "only a camera model uses it (model: kinect_v1, tof, ...)");
    }
    return;
  }
  const auto preset = camera::Preset(model);
  if (!preset) {
    std::string names = "gaussian";
    for (const auto& n : camera::PresetNames()) names += ", " + n;
    r.Fail("model", "unknown sensor model '" + model + "' (" + names + ")");
  }
  s->camera = *preset;
  if (r.Has("noise_sigma")) {
    r.Fail("noise_sigma", "only model gaussian uses it: the camera model sets the noise");
  }
  camera::DepthCameraModel& c = s->camera;
  r.Read("baseline", &c.baseline);
  r.Read("focal_px", &c.focal_px);
  r.Read("disparity_step", &c.disparity_step);
  r.Read("lateral_px", &c.lateral_px);
  r.Read("min_depth", &c.min_depth);
  r.Read("max_depth", &c.max_depth);
  r.Read("max_incidence_deg", &c.max_incidence_deg);
  RequirePositive(r, "baseline", c.baseline);
  RequirePositive(r, "focal_px", c.focal_px);
  RequirePositive(r, "disparity_step", c.disparity_step);
  RequireNonNegative(r, "lateral_px", c.lateral_px);
  RequireNonNegative(r, "min_depth", c.min_depth);
  if (!(c.max_depth > c.min_depth)) r.Fail("max_depth", "must exceed min_depth");
  if (!(c.max_incidence_deg > 0.0 && c.max_incidence_deg <= 90.0)) {
    r.Fail("max_incidence_deg", "must be in (0, 90]");
  }
}

void ReadSensor(Reader r, SensorOptions* s) {
  ReadCameraModel(r, s);
  r.Read("width", &s->width);
  r.Read("height", &s->height);
  r.Read("hfov_deg", &s->hfov_deg);
  r.Read("vfov_deg", &s->vfov_deg);
  r.Read("max_range", &s->max_range);
  r.Read("mount_height", &s->mount_height);
  r.Read("noise_sigma", &s->noise_sigma);
  r.Read("dropout", &s->dropout);
  long long seed = static_cast<long long>(s->seed);
  r.Read("seed", &seed);
  if (seed < 0) r.Fail("seed", "must not be negative");
  s->seed = static_cast<uint64_t>(seed);
  if (s->width < 1 || s->width > 8192) r.Fail("width", "must be in 1..8192");
  if (s->height < 1 || s->height > 8192) r.Fail("height", "must be in 1..8192");
  if (!(s->hfov_deg > 0.0 && s->hfov_deg < 170.0)) r.Fail("hfov_deg", "must be in (0, 170)");
  if (!(s->vfov_deg > 0.0 && s->vfov_deg < 170.0)) r.Fail("vfov_deg", "must be in (0, 170)");
  RequirePositive(r, "max_range", s->max_range);
  RequirePositive(r, "mount_height", s->mount_height);
  RequireNonNegative(r, "noise_sigma", s->noise_sigma);
  if (!(s->dropout >= 0.0 && s->dropout < 1.0)) r.Fail("dropout", "must be in [0, 1)");
}

void ReadOdometry(Reader r, OdometryOptions* o) {
  r.Read("enabled", &o->enabled);
  r.Read("rate", &o->rate_hz);
  r.Read("scale_error_percent", &o->scale_error_percent);
  r.Read("turn_scale_error_percent", &o->turn_scale_error_percent);
  r.Read("heading_drift_deg_per_m", &o->heading_drift_deg_per_m);
  r.Read("noise_m_per_sqrt_m", &o->noise_m_per_sqrt_m);
  r.Read("noise_deg_per_sqrt_m", &o->noise_deg_per_sqrt_m);
  r.Read("turn_noise_percent", &o->turn_noise_percent);
  long long seed = static_cast<long long>(o->seed);
  r.Read("seed", &seed);
  if (seed < 0) r.Fail("seed", "must not be negative");
  o->seed = static_cast<uint64_t>(seed);
  RequireNonNegative(r, "rate", o->rate_hz);
  const std::pair<const char*, double> systematic[] = {
      {"scale_error_percent", o->scale_error_percent},
      {"turn_scale_error_percent", o->turn_scale_error_percent},
      {"heading_drift_deg_per_m", o->heading_drift_deg_per_m}};
  for (const auto& [key, value] : systematic) {
    if (!(std::abs(value) < 50.0)) r.Fail(key, "must be finite and within +-50");
  }
  RequireNonNegative(r, "noise_m_per_sqrt_m", o->noise_m_per_sqrt_m);
  RequireNonNegative(r, "noise_deg_per_sqrt_m", o->noise_deg_per_sqrt_m);
  RequireNonNegative(r, "turn_noise_percent", o->turn_noise_percent);
}

}  // namespace

ServiceOptions ReadServiceOptions(Reader reader) {
  ServiceOptions o;
  reader.Read("rate_hz", &o.sim.rate_hz);
  RequirePositive(reader, "rate_hz", o.sim.rate_hz);
  reader.Read("start_delay", &o.start_delay);
  RequireNonNegative(reader, "start_delay", o.start_delay);
  reader.Read("drop_fraction", &o.drop_fraction);
  if (!(o.drop_fraction >= 0.0 && o.drop_fraction < 1.0)) {
    reader.Fail("drop_fraction", "must be in [0, 1)");
  }
  ReadWorld(reader.Child("world"), &o.sim.world);
  RouteOfGeneratedWorld(reader.Child("world"), o.sim.world, &o.sim.trajectory);
  ReadTrajectory(reader.Child("trajectory"), &o.sim.trajectory);
  ReadSensor(reader.Child("sensor"), &o.sim.sensor);
  ReadOdometry(reader.Child("odometry"), &o.odometry);
  reader.Finish();
  return o;
}

bool DropFrame(uint64_t seed, int64_t seq, double fraction) {
  if (fraction <= 0.0) return false;
  // SplitMix64's finaliser (Steele, Lea, Flood, OOPSLA 2014) over seed and seq.
  uint64_t z = seed * 0x9E3779B97F4A7C15ULL + static_cast<uint64_t>(seq) + 0x632BE59BD9B4E019ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  const double u = static_cast<double>(z >> 11) * 0x1.0p-53;  // uniform in [0, 1)
  return u < fraction;
}

ServiceOptions LoadServiceOptions(const std::string& file) {
  if (file.empty()) return ReadServiceOptions(Reader::FromString("", "(defaults)", "sim"));
  return ReadServiceOptions(Reader::Load(file, "sim"));
}

}  // namespace relplane::sim
