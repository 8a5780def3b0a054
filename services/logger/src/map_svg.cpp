#include <algorithm>
#include <cmath>
#include <map>

#include "relplane/eval/map_metrics.hpp"
#include "relplane/eval/report_json.hpp"
#include "relplane/eval/svg.hpp"
#include "svg_util.hpp"

namespace relplane::eval {
namespace {

constexpr double kMargin = 30.0;
constexpr double kTitleHeight = 34.0;
constexpr double kFooterHeight = 120.0;
constexpr const char* kGroupColors[] = {"#e07b00", "#8e44ad", "#16a085", "#c0392b",
                                        "#2c3e50", "#b8860b", "#d35400", "#7f8c8d"};

// World x-y (metres) to picture pixels; y grows up in the world and down in SVG.
struct View {
  double x_min = 0.0, y_max = 0.0, scale = 1.0, top = kTitleHeight;
  double X(double x) const { return kMargin + (x - x_min) * scale; }
  double Y(double y) const { return top + (y_max - y) * scale; }
};

struct Bounds {
  Eigen::Vector2d lo{1e300, 1e300};
  Eigen::Vector2d hi{-1e300, -1e300};
  void Add(const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool Empty() const { return lo.x() > hi.x(); }
};

std::string Polyline(const std::vector<PoseSample>& poses, const View& view, const char* style) {
  std::string points;
  double last_x = -1e9, last_y = -1e9;
  for (const PoseSample& p : poses) {
    const double x = view.X(p.position.x());
    const double y = view.Y(p.position.y());
    if (std::hypot(x - last_x, y - last_y) < 0.5) continue;  // below a pixel: skip
    points += svg::Format("%.1f,%.1f ", x, y);
    last_x = x;
    last_y = y;
  }
  if (points.empty()) return "";
  return "<polyline fill=\"none\" " + std::string(style) + " points=\"" + points + "\"/>\n";
}

std::string Walls(const std::vector<WallLine>& walls, const View& view, const char* style,
                  const char* what) {
  std::string out;
  for (const WallLine& w : walls) {
    out += svg::Format("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" %s>",
                       view.X(w.segment.a.x()), view.Y(w.segment.a.y()), view.X(w.segment.b.x()),
                       view.Y(w.segment.b.y()), style);
    out += svg::Format("<title>%s %lld</title></line>\n", what, static_cast<long long>(w.id));
  }
  return out;
}

// Lines from each member plane to its group's centroid, labelled X1, X2, ... (§II.B, Fig. 2).
std::string Groups(const MapSnapshot& map, const View& view) {
  std::map<int64_t, Eigen::Vector2d> anchor;  // plane id -> where its group line starts
  for (const PlaneRecord& p : map.planes) anchor[p.id] = p.centroid.head<2>();
  for (const WallLine& w : WallsOf(map.planes)) anchor[w.id] = w.segment.Midpoint();
  const std::map<int64_t, std::string> labels = GroupLabels(map);
  std::string lines, marks;
  int color = 0;
  for (const auto& [id, label] : labels) {
    const GroupRecord& g = *std::find_if(map.groups.begin(), map.groups.end(),
                                         [id = id](const GroupRecord& r) { return r.id == id; });
    std::vector<Eigen::Vector2d> ends;
    for (const int64_t m : g.members) {
      if (anchor.count(m)) ends.push_back(anchor[m]);
    }
    const char* stroke = kGroupColors[color++ % 8];
    if (ends.empty()) continue;
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const auto& e : ends) c += e;
    c /= static_cast<double>(ends.size());
    for (const auto& e : ends) {
      lines += svg::Line(
          view.X(e.x()), view.Y(e.y()), view.X(c.x()), view.Y(c.y()),
          svg::Format("stroke=\"%s\" stroke-width=\"1\" stroke-dasharray=\"4 3\"", stroke).c_str());
    }
    marks += svg::Format("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3\" fill=\"%s\"/>\n", view.X(c.x()),
                         view.Y(c.y()), stroke);
    marks += svg::Text(view.X(c.x()) + 5, view.Y(c.y()) - 5, label, "start",
                       svg::Format("fill=\"%s\" font-weight=\"bold\"", stroke).c_str());
  }
  return lines + marks;
}

// Two rows: the walls, then group links and trajectories.
std::string Legend(double y) {
  struct Item {
    const char* style;
    const char* text;
  };
  const Item rows[2][4] = {
      {{"stroke=\"#b0b0b0\" stroke-width=\"6\"", "true wall"},
       {"stroke=\"#b0b0b0\" stroke-width=\"1.5\" stroke-dasharray=\"2 2\"",
        "true wall above/below the sensor"},
       {"stroke=\"#1f5fbf\" stroke-width=\"2.5\"", "mapped wall"},
       {"stroke=\"#d81b60\" stroke-width=\"2.5\"", "mapped wall matching no true wall"}},
      {{"stroke=\"#e07b00\" stroke-width=\"1\" stroke-dasharray=\"4 3\"", "plane to group Xk"},
       {"stroke=\"#2a9d3a\" stroke-width=\"1.5\"", "true trajectory"},
       {"stroke=\"#d62828\" stroke-width=\"1.5\"", "estimated trajectory"},
       {nullptr, nullptr}},
  };
  std::string out;
  for (int row = 0; row < 2; ++row) {
    double x = kMargin;
    for (const Item& item : rows[row]) {
      if (item.text == nullptr) continue;
      out += svg::Line(x, y + 22 * row, x + 26, y + 22 * row, item.style);
      out += svg::Text(x + 32, y + 22 * row + 4, item.text);
      x += 56 + 7.0 * std::string(item.text).size();
    }
  }
  return out;
}

std::string ScaleBar(const View& view, double right, double y) {
  const double metres = NiceStep((right - kMargin) / view.scale, 5.0);
  const double length = metres * view.scale;
  const double x0 = right - length;
  std::string out = svg::Line(x0, y, right, y, "stroke=\"black\" stroke-width=\"2\"");
  out += svg::Line(x0, y - 5, x0, y + 5, "stroke=\"black\" stroke-width=\"2\"");
  out += svg::Line(right, y - 5, right, y + 5, "stroke=\"black\" stroke-width=\"2\"");
  out += svg::Text(0.5 * (x0 + right), y - 8, svg::Format("%g m", metres), "middle");
  return out;
}

std::string Caption(const RunMetrics& m) {
  std::string text = svg::Format("iterations %lld", static_cast<long long>(m.run.estimate_poses));
  if (std::isfinite(m.trajectory.ate_rmse_m)) {
    text += svg::Format("   ATE RMSE %.3f m (aligned %.3f m)", m.trajectory.ate_rmse_m,
                        m.trajectory.ate_aligned_rmse_m);
  }
  if (m.map.has_truth) {
    text += svg::Format(
        "   walls mapped %lld/%lld, duplicates %lld, spurious %lld, missed %lld",
        static_cast<long long>(m.map.walls_mapped), static_cast<long long>(m.map.expected_walls),
        static_cast<long long>(m.map.duplicates), static_cast<long long>(m.map.spurious),
        static_cast<long long>(m.map.missed));
  }
  return text;
}

}  // namespace

double NiceStep(double span, double target_count) {
  if (!(span > 0.0) || !(target_count > 0.0)) return 1.0;
  const double raw = span / target_count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double f : {1.0, 2.0, 5.0}) {
    if (f * power >= raw) return f * power;
  }
  return 10.0 * power;
}

std::string RenderMapSvg(const MapPicture& pic) {
  static const MapSnapshot kEmptyMap;
  static const std::vector<PoseSample> kNoPoses;
  const MapSnapshot& world = pic.world ? *pic.world : kEmptyMap;
  const MapSnapshot& map = pic.map ? *pic.map : kEmptyMap;
  const std::vector<PoseSample>& truth = pic.truth ? *pic.truth : kNoPoses;
  const std::vector<PoseSample>& estimate = pic.estimate ? *pic.estimate : kNoPoses;
  const std::vector<WallLine> true_walls = WallsOf(world.planes);
  const std::vector<WallLine> mapped_walls = WallsOf(map.planes);

  Bounds b;
  for (const auto* walls : {&true_walls, &mapped_walls}) {
    for (const WallLine& w : *walls) {
      b.Add(w.segment.a);
      b.Add(w.segment.b);
    }
  }
  for (const auto* poses : {&truth, &estimate}) {
    for (const PoseSample& p : *poses) b.Add(p.position.head<2>());
  }
  if (b.Empty()) b.Add(Eigen::Vector2d::Zero());
  b.lo -= Eigen::Vector2d(0.5, 0.5);
  b.hi += Eigen::Vector2d(0.5, 0.5);

  const double width = std::max(pic.width_px, 400.0);
  View view;
  view.x_min = b.lo.x();
  view.y_max = b.hi.y();
  const Eigen::Vector2d span = b.hi - b.lo;
  // Fit the width; very tall worlds are limited to 1.2 times the width.
  view.scale = std::min((width - 2 * kMargin) / span.x(), 1.2 * width / span.y());
  const double plot_height = span.y() * view.scale;
  const double height = kTitleHeight + plot_height + kFooterHeight;

  std::string out = svg::Header(width, height);
  out += svg::Text(kMargin, 22, "relplane map: x-y plane, world frame, metres", "start",
                   "font-size=\"15\" font-weight=\"bold\"");
  // A light grid at the scale bar's step gives the eye the units everywhere.
  // From the larger span: a hostile pose far along y must not make millions of lines.
  const double step = NiceStep(std::max(span.x(), span.y()), 10.0);
  std::string grid;
  const char* tick_style = "fill=\"#999999\" font-size=\"10\"";
  // Integer multiples of the step, so labels print as round numbers.
  // At most kMaxGridLines a direction: far from the origin (a hostile pose at 1e17 m) k * step
  // stops changing when k grows, and the loop would not end (found by relplane-fuzz-logger).
  constexpr int kMaxGridLines = 100;
  int lines = 0;
  for (long k = std::lround(std::ceil(b.lo.x() / step));
       k * step <= b.hi.x() && lines < kMaxGridLines; ++k, ++lines) {
    const double x = k * step;
    grid += svg::Line(view.X(x), view.Y(b.lo.y()), view.X(x), view.Y(b.hi.y()),
                      "stroke=\"#eeeeee\" stroke-width=\"1\"");
    grid += svg::Text(view.X(x), view.Y(b.lo.y()) - 3, svg::Format("%g", x + 0.0), "middle",
                      tick_style);
  }
  lines = 0;
  for (long k = std::lround(std::ceil(b.lo.y() / step));
       k * step <= b.hi.y() && lines < kMaxGridLines; ++k, ++lines) {
    const double y = k * step;
    grid += svg::Line(view.X(b.lo.x()), view.Y(y), view.X(b.hi.x()), view.Y(y),
                      "stroke=\"#eeeeee\" stroke-width=\"1\"");
    grid += svg::Text(view.X(b.lo.x()) + 3, view.Y(y) - 3, svg::Format("%g", y + 0.0), "start",
                      tick_style);
  }
  out += "<g id=\"grid\">\n" + grid + "</g>\n";
  // Walls the sensor's height passes through are drawn solid; lintels and the like thin.
  const double sensor_z = SensorHeight(truth);
  std::vector<WallLine> at_height, off_height;
  for (const WallLine& w : true_walls) {
    (SpansHeight(w, sensor_z) ? at_height : off_height).push_back(w);
  }
  out += "<g id=\"true-walls\">\n" +
         Walls(at_height, view, "stroke=\"#b0b0b0\" stroke-width=\"6\" stroke-linecap=\"butt\"",
               "true wall") +
         Walls(off_height, view, "stroke=\"#b0b0b0\" stroke-width=\"1.5\" stroke-dasharray=\"2 2\"",
               "true wall above or below the sensor") +
         "</g>\n";
  out += "<g id=\"groups\">\n" + Groups(map, view) + "</g>\n";
  // Mapped walls that match no true wall stand out (the metrics' spurious planes).
  std::vector<WallLine> matched, spurious;
  for (const WallLine& w : mapped_walls) {
    const bool is_spurious =
        pic.metrics != nullptr && std::count(pic.metrics->map.spurious_ids.begin(),
                                             pic.metrics->map.spurious_ids.end(), w.id) > 0;
    (is_spurious ? spurious : matched).push_back(w);
  }
  out += "<g id=\"mapped-walls\">\n" +
         Walls(matched, view, "stroke=\"#1f5fbf\" stroke-width=\"2.5\" stroke-linecap=\"round\"",
               "mapped plane") +
         Walls(spurious, view, "stroke=\"#d81b60\" stroke-width=\"2.5\" stroke-linecap=\"round\"",
               "mapped plane matching no true wall") +
         "</g>\n";
  out += "<g id=\"trajectories\">\n";
  out += Polyline(truth, view, "stroke=\"#2a9d3a\" stroke-width=\"1.5\"");
  out += Polyline(estimate, view, "stroke=\"#d62828\" stroke-width=\"1.5\"");
  if (!truth.empty()) {
    out += svg::Format(
        "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"#2a9d3a\"><title>start</title></circle>\n",
        view.X(truth.front().position.x()), view.Y(truth.front().position.y()));
  }
  out += "</g>\n";

  const double footer = kTitleHeight + plot_height;
  out += Legend(footer + 26);
  out += ScaleBar(view, width - kMargin, footer + 80);
  if (pic.metrics != nullptr) out += svg::Text(kMargin, footer + 108, Caption(*pic.metrics));
  out += "</svg>\n";
  return out;
}

}  // namespace relplane::eval
