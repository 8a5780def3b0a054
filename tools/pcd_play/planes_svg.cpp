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
  static int panel = 0;
  const std::string clip = "panel" + std::to_string(panel++);
  svg << "<g transform='translate(" << ox << ",30)'>\n";
  svg << "<clipPath id='" << clip << "'><rect width='" << w << "' height='" << h
      << "'/></clipPath>\n";
  svg << "<text x='0' y='-10' font-size='14'>" << title << "</text>\n";
  svg << "<g shape-rendering='crispEdges'>\n";
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
  svg << "</g>\n<g clip-path='url(#" << clip << ")'>\n";  // outlines may leave the image
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
  }
  svg << "</g>\n";
  for (size_t k = 0; k < r.planes.size(); ++k) {
    const auto& p = r.planes[k];
    char line[200];
    std::snprintf(line, sizeof line, "n=(%.2f, %.2f, %.2f) d=%.2f m, %d pts, rms %.1f mm",
                  p.normal.x(), p.normal.y(), p.normal.z(), p.d, p.num_points, p.rms * 1000);
    svg << "<rect x='0' y='" << h + 8 + 16 * k << "' width='12' height='12' fill='"
        << Colour(static_cast<int>(k)) << "'/><text x='18' y='" << h + 18 + 16 * k
        << "' font-size='12'>" << line << "</text>\n";
  }
  svg << "</g>\n";
}

// The same picture as a raster (binary PPM, one pixel per point): panels side by side, the
// extent outlines drawn in white over the labels.
class Raster {
 public:
  Raster(int width, int height) : w_(width), h_(height), rgb_(3 * width * height, 255) {}
  void Set(int x, int y, const char* hex) {
    if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
    for (int c = 0; c < 3; ++c) {
      rgb_[3 * (y * w_ + x) + c] =
          static_cast<uint8_t>(std::stoi(std::string(hex + 1 + 2 * c, 2), nullptr, 16));
    }
  }
  void Line(double x0, double y0, double x1, double y1, int xmin, int xmax, const char* hex) {
    const int steps =
        static_cast<int>(std::min(4000.0, std::max(std::fabs(x1 - x0), std::fabs(y1 - y0))) + 1);
    for (int i = 0; i <= steps; ++i) {
      const double t = static_cast<double>(i) / steps;
      const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0)));
      const int y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
      if (x < xmin || x >= xmax) continue;
      for (int d = -1; d <= 1; ++d) Set(x + d, y, hex), Set(x, y + d, hex);
    }
  }
  bool Write(const std::string& path) const {
    std::ofstream out(path, std::ios::binary);
    out << "P6\n" << w_ << " " << h_ << "\n255\n";
    out.write(reinterpret_cast<const char*>(rgb_.data()),
              static_cast<std::streamsize>(rgb_.size()));
    return static_cast<bool>(out);
  }

 private:
  int w_, h_;
  std::vector<uint8_t> rgb_;
};

void Draw(Raster* raster, const pcd::PcdCloud& pcd, const segmenter::Result& r, int ox, double f) {
  for (int y = 0; y < pcd.height; ++y) {
    for (int x = 0; x < pcd.width; ++x) {
      const size_t i = static_cast<size_t>(y) * pcd.width + x;
      raster->Set(ox + x, y, std::isfinite(pcd.x[i]) ? Colour(r.labels[i]) : "#000000");
    }
  }
  for (const auto& p : r.planes) {
    for (size_t k = 0; k < p.vertices.size(); ++k) {
      double u0, v0, u1, v1;
      const auto& a = p.vertices[k];
      const auto& b = p.vertices[(k + 1) % p.vertices.size()];
      if (!Project(a, f, pcd.width / 2.0, pcd.height / 2.0, &u0, &v0) ||
          !Project(b, f, pcd.width / 2.0, pcd.height / 2.0, &u1, &v1)) {
        continue;
      }
      raster->Line(ox + u0, v0, ox + u1, v1, ox, ox + pcd.width, "#ffffff");
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  cli::Parser parser{"relplane-pcd-planes-svg: draw the planes the segmenter finds in PCD frames"};
  std::vector<std::string> files;
  std::string out = "planes.svg", config;
  bool optical = false;
  double focal = 525.0;
  parser.Add("files", &files, "organized PCD files").Required();
  parser.Add("--out", &out, "SVG file to write");
  parser.Add("--config", &config, "YAML file with a `segmenter` section");
  parser.AddFlag("--optical", &optical, "the files are in the optical frame");
  parser.Add("--focal", &focal, "focal length in pixels, for the extent outlines");
  std::string ppm;
  parser.Add("--ppm", &ppm, "also write the picture as a PPM raster, one pixel per point");
  if (auto code = parser.Parse(argc, argv)) return *code;
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
  std::vector<std::pair<pcd::PcdCloud, segmenter::Result>> frames;
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
    if (!ppm.empty()) frames.emplace_back(std::move(pcd), r);
    width = x;
    height = std::max(height, pcd.height + 60.0 + 16.0 * r.planes.size());
  }
  if (!ppm.empty() && !frames.empty()) {
    const int fw = frames[0].first.width, fh = frames[0].first.height;
    Raster raster(static_cast<int>(frames.size()) * (fw + 20) - 20, fh);
    for (size_t k = 0; k < frames.size(); ++k) {
      Draw(&raster, frames[k].first, frames[k].second, static_cast<int>(k) * (fw + 20), focal);
    }
    if (!raster.Write(ppm)) return 1;
  }
  std::ofstream svg(out);
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
      << "' font-family='sans-serif'>\n<rect width='100%' height='100%' fill='white'/>\n"
      << body.str() << "</svg>\n";
  return svg ? 0 : 1;
}
