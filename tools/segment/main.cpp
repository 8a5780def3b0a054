// relplane-segment: segments depth frames from files (PCD) with the EM segmenter and prints
// each frame's planes as a table; --json and --svg write them (docs/segment.md).

#include <fstream>
#include <iostream>

#include "options_yaml.hpp"  // services/segmenter: the `segmenter` section
#include "relplane/common/cli.hpp"
#include "relplane/segment/depth_frame.hpp"
#include "relplane/segment/plane_report.hpp"
#include "relplane/segment/planes_svg.hpp"
#include "relplane/segment/segment_frame.hpp"

namespace {

using namespace relplane;

bool WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (out) return true;
  std::cerr << "relplane-segment: cannot write " << path << "\n";
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  cli::Parser parser{
      "Segments depth frames (PCD) with relplane's EM segmenter, each seeded by the one before "
      "as in a stream, and prints each frame's planes: normal, d (normal . p + d = 0), "
      "supporting points, RMS and extent size, in the sensor frame (x forward, y left, z up).",
      "relplane-segment"};
  std::vector<std::string> files;
  std::string config, json_file, svg_file;
  bool optical = false;
  double focal = 525.0;
  parser.Add("files", &files, "Depth frames: .pcd (ascii, binary, binary_compressed)").Required();
  parser.Add("--config", &config, "Scenario or YAML file with a `segmenter` section");
  parser.AddFlag("--optical", &optical,
                 "The files are in the optical frame (x right, y down, z forward)");
  parser.Add("--json", &json_file, "Write every frame's planes as JSON to this file");
  parser.Add("--svg", &svg_file, "Draw the planes of organized frames into this SVG file");
  parser.Add("--focal", &focal, "Focal length in pixels, for the --svg outlines").Positive();
  if (const auto code = parser.Parse(argc, argv)) return *code;

  segmenter::ServiceOptions options;
  try {
    options = segmenter::LoadServiceOptions(config);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return cli::kExitConfig;
  }
  options.segmenter.keep_labels = !svg_file.empty();
  segmenter::Segmenter seg(options.segmenter);
  std::vector<segment::FramePlanes> results;
  std::vector<segment::LabelledFrame> pictures;
  for (const std::string& file : files) {
    segment::DepthFrame frame;
    try {
      frame = segment::ReadDepthFrame(file, {optical});
    } catch (const segment::FrameError& e) {
      std::cerr << e.what() << "\n";
      return 1;
    }
    std::vector<int32_t> labels;
    results.push_back(segment::SegmentFrame(seg, frame, svg_file.empty() ? nullptr : &labels));
    std::cout << segment::PlaneTable(results.back()) << std::flush;
    if (svg_file.empty()) continue;
    if (!frame.Organized()) {
      std::cerr << file << ": not an organized cloud: left out of the SVG\n";
      continue;
    }
    pictures.push_back({std::move(frame), std::move(labels), results.back().planes});
  }
  if (!json_file.empty() && !WriteText(json_file, segment::PlanesJson(results))) return 1;
  if (!svg_file.empty() && !WriteText(svg_file, segment::PlanesSvg(pictures, focal))) return 1;
  return 0;
}
