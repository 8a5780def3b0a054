#include "relplane/segment/planes_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "relplane/segment/plane_report.hpp"

namespace relplane::segment {
namespace {

const char* const kPalette[] = {"#e6194b", "#3cb44b", "#ffe119", "#4363d8", "#f58231", "#911eb4",
                                "#46f0f0", "#f032e6", "#bcf60c", "#fabebe", "#008080", "#9a6324"};
constexpr int kBlock = 4;  // pixels per drawn cell

const char* Colour(int label) {
  if (label == -2) return "#000000";  // no depth
  if (label < 0) return "#9a9a9a";
  return kPalette[label % (sizeof kPalette / sizeof kPalette[0])];
}

// Sensor frame (x forward, y left, z up) -> pixel, with the optical frame's pinhole.
bool Project(const Eigen::Vector3f& p, double f, double cx, double cy, double* u, double* v) {
  if (p.x() <= 0.05f) return false;
  *u = cx + f * (-p.y()) / p.x();
  *v = cy + f * (-p.z()) / p.x();
  return true;
}

// The label most of a block's pixels have (-2: no depth).
int BlockLabel(const LabelledFrame& lf, int bx, int by) {
  std::map<int, int> votes;
  for (int y = by * kBlock; y < (by + 1) * kBlock; ++y) {
    for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) {
      const size_t i = static_cast<size_t>(y) * lf.frame.width + x;
      ++votes[std::isfinite(lf.frame.x[i]) ? lf.labels[i] : -2];
    }
  }
  int best = -2, count = -1;
  for (const auto& [label, n] : votes) {
    if (n > count) best = label, count = n;
  }
  return best;
}

// Label cells, run-length coded along each row of blocks.
void Pixels(std::ostream& svg, const LabelledFrame& lf) {
  const int columns = lf.frame.width / kBlock;
  for (int by = 0; by < lf.frame.height / kBlock; ++by) {
    int run_start = 0;
    const char* run_colour = nullptr;
    for (int bx = 0; bx <= columns; ++bx) {
      const char* colour = bx < columns ? Colour(BlockLabel(lf, bx, by)) : nullptr;
      if (colour == run_colour) continue;
      if (run_colour != nullptr) {
        svg << "<rect x='" << run_start * kBlock << "' y='" << by * kBlock << "' width='"
            << (bx - run_start) * kBlock << "' height='" << kBlock << "' fill='" << run_colour
            << "'/>\n";
      }
      run_start = bx;
      run_colour = colour;
    }
  }
}

void Panel(std::ostream& svg, const LabelledFrame& lf, double ox, int index, double f) {
  const int w = lf.frame.width, h = lf.frame.height;
  const std::string clip = "panel" + std::to_string(index);
  svg << "<g transform='translate(" << ox << ",30)'>\n";
  svg << "<clipPath id='" << clip << "'><rect width='" << w << "' height='" << h
      << "'/></clipPath>\n";
  svg << "<text x='0' y='-10' font-size='14'>" << lf.frame.name << ": " << lf.planes.size()
      << " planes</text>\n";
  svg << "<g shape-rendering='crispEdges'>\n";
  Pixels(svg, lf);
  svg << "</g>\n<g clip-path='url(#" << clip << ")'>\n";  // outlines may leave the image
  for (size_t k = 0; k < lf.planes.size(); ++k) {
    std::ostringstream points;
    bool in_front = true;
    for (const Eigen::Vector3f& v : lf.planes[k].vertices) {
      double u = 0, vv = 0;
      in_front &= Project(v, f, w / 2.0, h / 2.0, &u, &vv);
      points << u << "," << vv << " ";
    }
    if (!in_front) continue;
    svg << "<polygon points='" << points.str() << "' fill='none' stroke='white' "
        << "stroke-width='2.5'/>\n<polygon points='" << points.str() << "' fill='none' stroke='"
        << Colour(static_cast<int>(k)) << "' stroke-width='1.2'/>\n";
  }
  svg << "</g>\n";
  for (size_t k = 0; k < lf.planes.size(); ++k) {
    const segmenter::DetectedPlane& p = lf.planes[k];
    const Eigen::Vector2f size = ExtentSize(p);
    char line[200];
    std::snprintf(line, sizeof line,
                  "n=(%.2f, %.2f, %.2f) d=%.2f m, %d pts, rms %.1f mm, %.2f x %.2f m", p.normal.x(),
                  p.normal.y(), p.normal.z(), p.d, p.num_points, p.rms * 1000, size.x(), size.y());
    svg << "<rect x='0' y='" << h + 8 + 16 * k << "' width='12' height='12' fill='"
        << Colour(static_cast<int>(k)) << "'/><text x='18' y='" << h + 18 + 16 * k
        << "' font-size='12'>" << line << "</text>\n";
  }
  svg << "</g>\n";
}

}  // namespace

std::string PlanesSvg(const std::vector<LabelledFrame>& frames, double focal_px) {
  std::ostringstream body;
  double x = 10, height = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    Panel(body, frames[k], x, static_cast<int>(k), focal_px);
    x += frames[k].frame.width + 20;
    height = std::max(height, frames[k].frame.height + 60.0 + 16.0 * frames[k].planes.size());
  }
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << x << "' height='" << height
      << "' font-family='sans-serif'>\n<rect width='100%' height='100%' fill='white'/>\n"
      << body.str() << "</svg>\n";
  return svg.str();
}

}  // namespace relplane::segment
