#include <algorithm>
#include <cmath>

#include "relplane/eval/svg.hpp"
#include "svg_util.hpp"

namespace relplane::eval {
namespace {

constexpr double kLeft = 70.0;
constexpr double kRight = 20.0;
constexpr double kTop = 40.0;
constexpr double kBottom = 50.0;
constexpr double kPlotHeight = 300.0;

struct Axes {
  double t0 = 0.0, t1 = 1.0, e1 = 1.0, width = 800.0;
  double X(double t) const { return kLeft + (t - t0) / (t1 - t0) * width; }
  double Y(double e) const { return kTop + kPlotHeight - e / e1 * kPlotHeight; }
};

std::string Series(const std::vector<ErrorSample>& errors, const Axes& axes, bool aligned,
                   const char* style) {
  std::string points;
  double last_x = -1e9;
  for (const ErrorSample& e : errors) {
    const double x = axes.X(e.t_s);
    // At most about two points per pixel column keep large runs small.
    if (x - last_x < 0.5) continue;
    points += svg::Format("%.1f,%.1f ", x, axes.Y(aligned ? e.aligned_m : e.position_m));
    last_x = x;
  }
  if (points.empty()) return "";
  return "<polyline fill=\"none\" " + std::string(style) + " points=\"" + points + "\"/>\n";
}

// A panel of a signed error (along or across the truth's heading) with the estimate's own
// +-2 sigma band shaded behind it: where the error leaves the band, the covariance was too sure.
constexpr double kBandHeight = 150.0;
constexpr double kBandGap = 45.0;

std::string SignedPanel(const std::vector<ErrorSample>& errors, const Axes& time, double top,
                        bool along, const char* title) {
  const auto value = [along](const ErrorSample& e) { return along ? e.along_m : e.across_m; };
  const auto sigma = [along](const ErrorSample& e) {
    return along ? e.sigma_along_m : e.sigma_across_m;
  };
  double e_max = 0.0;
  for (const ErrorSample& e : errors) e_max = std::max(e_max, std::abs(value(e)));
  const double step = NiceStep(std::max(e_max, 0.01), 2.0);
  const double e1 = std::max(step, std::ceil(e_max / step) * step);
  // The band is clipped to the panel: a direction nothing constrains has the prior's sigma.
  const auto y = [&](double v) {
    return top + 0.5 * kBandHeight - std::clamp(v, -e1, e1) / e1 * 0.5 * kBandHeight;
  };
  std::string out = svg::Text(kLeft, top - 8, title, "start", "font-weight=\"bold\"");
  for (const double v : {-e1, 0.0, e1}) {
    out +=
        svg::Line(kLeft, y(v), kLeft + time.width, y(v), "stroke=\"#eeeeee\" stroke-width=\"1\"");
    out += svg::Text(kLeft - 6, y(v) + 4, svg::Format("%g", v), "end");
  }
  std::string upper, lower, line;
  double last_x = -1e9;
  for (const ErrorSample& e : errors) {
    const double x = time.X(e.t_s);
    if (x - last_x < 0.5) continue;
    upper += svg::Format("%.1f,%.1f ", x, y(2.0 * sigma(e)));
    lower = svg::Format("%.1f,%.1f ", x, y(-2.0 * sigma(e))) + lower;
    line += svg::Format("%.1f,%.1f ", x, y(value(e)));
    last_x = x;
  }
  if (!line.empty()) {
    out += "<polygon fill=\"#f4c542\" fill-opacity=\"0.35\" stroke=\"none\" points=\"" + upper +
           lower + "\"/>\n";
    out += "<polyline fill=\"none\" stroke=\"#d62828\" stroke-width=\"1.2\" points=\"" + line +
           "\"/>\n";
  }
  out += svg::Line(kLeft, top, kLeft, top + kBandHeight, "stroke=\"black\" stroke-width=\"1\"");
  return out;
}

}  // namespace

std::string RenderErrorSvg(const TrajectoryMetrics& trajectory, double width_px) {
  const std::vector<ErrorSample>& errors = trajectory.errors;
  const double width = std::max(width_px, 400.0);
  Axes axes;
  axes.width = width - kLeft - kRight;
  double e_max = 0.0;
  if (!errors.empty()) {
    axes.t0 = errors.front().t_s;
    axes.t1 = std::max(errors.back().t_s, axes.t0 + 1e-3);
    for (const ErrorSample& e : errors) e_max = std::max({e_max, e.position_m, e.aligned_m});
  }
  const double e_step = NiceStep(std::max(e_max, 0.01), 5.0);
  axes.e1 = std::max(e_step, std::ceil(e_max / e_step) * e_step);
  const double t_step = NiceStep(axes.t1 - axes.t0, 8.0);

  const double band_top = kTop + kPlotHeight + kBottom + kBandGap;
  const double height = band_top + 2.0 * (kBandHeight + kBandGap);
  std::string out = svg::Header(width, height);
  out += svg::Text(kLeft, 24, "Position error against truth (x-y), matched by seq", "start",
                   "font-size=\"15\" font-weight=\"bold\"");
  // At most kMaxTicks an axis: far from zero (a hostile utime) k * step stops changing as k
  // grows and the loop would not end (the same flaw relplane-fuzz-logger found in map.svg).
  constexpr long kMaxTicks = 100;
  for (long k = 0; k * e_step <= axes.e1 + 1e-9 && k < kMaxTicks; ++k) {
    const double e = k * e_step;
    out += svg::Line(kLeft, axes.Y(e), kLeft + axes.width, axes.Y(e),
                     "stroke=\"#eeeeee\" stroke-width=\"1\"");
    out += svg::Text(kLeft - 6, axes.Y(e) + 4, svg::Format("%g", e), "end");
  }
  const long t_first = std::lround(std::ceil(axes.t0 / t_step));
  for (long k = t_first; k * t_step <= axes.t1 + 1e-9 && k - t_first < kMaxTicks; ++k) {
    const double t = k * t_step;
    out += svg::Line(axes.X(t), kTop + kPlotHeight, axes.X(t), kTop + kPlotHeight + 5,
                     "stroke=\"black\" stroke-width=\"1\"");
    out += svg::Text(axes.X(t), kTop + kPlotHeight + 18, svg::Format("%g", t), "middle");
  }
  out += svg::Line(kLeft, kTop, kLeft, kTop + kPlotHeight, "stroke=\"black\" stroke-width=\"1\"");
  out += svg::Line(kLeft, kTop + kPlotHeight, kLeft + axes.width, kTop + kPlotHeight,
                   "stroke=\"black\" stroke-width=\"1\"");
  out +=
      svg::Text(kLeft + 0.5 * axes.width, kTop + kPlotHeight + kBottom - 10, "time (s)", "middle");
  out += svg::Format(
      "<text x=\"18\" y=\"%.1f\" text-anchor=\"middle\" transform=\"rotate(-90 18 %.1f)\">"
      "position error (m)</text>\n",
      kTop + 0.5 * kPlotHeight, kTop + 0.5 * kPlotHeight);

  if (errors.empty()) {
    out += svg::Text(kLeft + 0.5 * axes.width, kTop + 0.5 * kPlotHeight,
                     "no pose matched to truth yet", "middle", "fill=\"#888888\"");
  }
  out += Series(errors, axes, false, "stroke=\"#d62828\" stroke-width=\"1.5\"");
  out += Series(errors, axes, true,
                "stroke=\"#1f5fbf\" stroke-width=\"1.2\" stroke-dasharray=\"5 3\"");

  out += SignedPanel(errors, axes, band_top, true,
                     "Along the true heading (m), shaded: the estimate's own +-2 sigma");
  out += SignedPanel(errors, axes, band_top + kBandHeight + kBandGap, false,
                     "Across the true heading, to the left (m), shaded: +-2 sigma");

  const double lx = kLeft + axes.width - 260;
  out += svg::Line(lx, kTop + 14, lx + 26, kTop + 14, "stroke=\"#d62828\" stroke-width=\"1.5\"");
  out += svg::Text(lx + 32, kTop + 18, "no alignment (first pose anchors)");
  out += svg::Line(lx, kTop + 34, lx + 26, kTop + 34,
                   "stroke=\"#1f5fbf\" stroke-width=\"1.2\" stroke-dasharray=\"5 3\"");
  out += svg::Text(lx + 32, kTop + 38, "after SE(2) alignment");
  out += "</svg>\n";
  return out;
}

}  // namespace relplane::eval
