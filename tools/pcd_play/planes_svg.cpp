// relplane-pcd-planes-svg: segments organized PCD frames and draws the planes found, in the
// image plane, one panel per frame: pixels coloured by plane (grey: no plane, black: invalid)
// and each plane's extent polygon projected with the camera's intrinsics.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "options_yaml.hpp"  // services/segmenter: the `segmenter` section
#include "relplane/common/cli.hpp"
#include "relplane/pcd/pcd_reader.hpp"
#include "relplane/segmenter/segmenter.hpp"

namespace {

using namespace relplane;

const char* const kPalette[] = {"#e6194b", "#3cb44b", "#ffe119", "#4363d8", "#f58231", "#911eb4",
                                "#46f0f0", "#f032e6", "#bcf60c", "#fabebe", "#008080", "#9a6324"};
constexpr int kBlock = 4;  // pixels per drawn cell

const char* Colour(int label) {
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

void Panel(std::ostream& svg, const pcd::PcdCloud& pcd, const segmenter::Result& r, double ox,
           const std::string& title, double f) {
  const int w = pcd.width, h = pcd.height;
  svg << "<g transform='translate(" << ox << ",30)'>\n";
  svg << "<text x='0' y='-10' font-size='14'>" << title << "</text>\n";
  // Label per block: the most common label of its pixels.
  for (int by = 0; by < h / kBlock; ++by) {
    int run_start = 0;
    std::string run_colour;
    for (int bx = 0; bx <= w / kBlock; ++bx) {
      std::string colour = "";
      if (bx < w / kBlock) {
        std::map<int, int> votes;
        for (int y = by * kBlock; y < (by + 1) * kBlock; ++y) {
          for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) {
            const size_t i = static_cast<size_t>(y) * w + x;
            const bool valid = std::isfinite(pcd.x[i]);
            ++votes[valid ? r.labels[i] : -2];
          }
        }
        int best = -2, count = -1;
        for (const auto& [label, n] : votes) {
          if (n > count) best = label, count = n;
        }
        colour = best == -2 ? "#000000" : Colour(best);
      }
      if (colour != run_colour) {
        if (!run_colour.empty()) {
          svg << "<rect x='" << run_start * kBlock << "' y='" << by * kBlock << "' width='"
              << (bx - run_start) * kBlock << "' height='" << kBlock << "' fill='" << run_colour
              << "'/>\n";
        }
        run_start = bx;
        run_colour = colour;
      }
    }
  }
  for (size_t k = 0; k < r.planes.size(); ++k) {
    const auto& p = r.planes[k];
    std::ostringstream pts;
    bool ok = true;
    for (const auto& v : p.vertices) {
      double u = 0, vv = 0;
      ok &= Project(v, f, w / 2.0, h / 2.0, &u, &vv);
      pts << u << "," << vv << " ";
    }
    if (ok) {
      svg << "<polygon points='" << pts.str() << "' fill='none' stroke='white' "
          << "stroke-width='2.5'/>\n<polygon points='" << pts.str() << "' fill='none' stroke='"
          << Colour(static_cast<int>(k)) << "' stroke-width='1.2'/>\n";
    }
    char line[200];
    std::snprintf(line, sizeof line, "n=(%.2f, %.2f, %.2f) d=%.2f m, %d pts, rms %.1f mm",
                  p.normal.x(), p.normal.y(), p.normal.z(), p.d, p.num_points, p.rms * 1000);
    svg << "<rect x='0' y='" << h + 8 + 16 * k << "' width='12' height='12' fill='"
        << Colour(static_cast<int>(k)) << "'/><text x='18' y='" << h + 18 + 16 * k
        << "' font-size='12'>" << line << "</text>\n";
  }
  svg << "</g>\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"relplane-pcd-planes-svg: draw the planes the segmenter finds in PCD frames"};
  std::vector<std::string> files;
  std::string out = "planes.svg", config;
  bool optical = false;
  double focal = 525.0;
  app.add_option("files", files, "organized PCD files")->required();
  app.add_option("--out", out, "SVG file to write");
  app.add_option("--config", config, "YAML file with a `segmenter` section");
  app.add_flag("--optical", optical, "the files are in the optical frame");
  app.add_option("--focal", focal, "focal length in pixels, for the extent outlines");
  if (auto code = cli::Parse(app, argc, argv)) return *code;
  segmenter::ServiceOptions options;
  try {
    options = segmenter::LoadServiceOptions(config);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return cli::kExitConfig;
  }
  options.segmenter.keep_labels = true;
  segmenter::Segmenter seg(options.segmenter);
  std::ostringstream body;
  double x = 10, width = 0, height = 0;
  for (const auto& file : files) {
    pcd::PcdCloud pcd;
    try {
      pcd = pcd::ReadPcd(file);
    } catch (const pcd::PcdError& e) {
      std::cerr << e.what() << "\n";
      return 1;
    }
    if (pcd.height < 2) {
      std::cerr << file << ": not an organized cloud\n";
      return 1;
    }
    if (optical) pcd::OpticalToSensor(&pcd);
    segmenter::Cloud cloud;
    cloud.x = pcd.x;
    cloud.y = pcd.y;
    cloud.z = pcd.z;
    const segmenter::Result r = seg.Segment(cloud);
    const std::string name = file.substr(file.find_last_of('/') + 1);
    Panel(body, pcd, r, x, name + ": " + std::to_string(r.planes.size()) + " planes", focal);
    x += pcd.width + 20;
    width = x;
    height = std::max(height, pcd.height + 60.0 + 16.0 * r.planes.size());
  }
  std::ofstream svg(out);
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
      << "' font-family='sans-serif'>\n<rect width='100%' height='100%' fill='white'/>\n"
      << body.str() << "</svg>\n";
  return svg ? 0 : 1;
}
