#include "relplane/plane_truth/labelled_planes.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <map>
#include <stdexcept>

namespace relplane::plane_truth {
namespace {

constexpr double kMostOfIt = 0.5;
constexpr double kMaxAngleDeg = 5.0;
constexpr double kMaxOffset = 0.03;  // metres, at the label's points' centroid
// A second detection along the label holding this share of its points splits it.
constexpr double kSplitShare = 0.2;

double Offset(const segmenter::DetectedPlane& p, const Label& l) {
  return std::fabs(p.normal.cast<double>().dot(l.centroid) + p.d);
}

bool Along(const segmenter::DetectedPlane& p, const Label& l) {
  return PlaneAngleDeg(p.normal.cast<double>(), l.normal) < kMaxAngleDeg &&
         Offset(p, l) < kMaxOffset;
}

}  // namespace

std::vector<Label> LoadLabels(const std::string& file, const pcd::PcdCloud& c) {
  const YAML::Node root = YAML::LoadFile(file);  // JSON is YAML
  std::vector<Label> labels;
  for (const auto& plane : root["planes"]) {
    Label l;
    l.name = plane["name"].as<std::string>();
    const auto n = plane["normal"].as<std::vector<double>>();
    l.normal = Eigen::Vector3d(n[0], n[1], n[2]);
    l.d = plane["d"].as<double>();
    for (const auto& box : plane["boxes"]) {
      const auto b = box.as<std::vector<int>>();
      if (b.size() != 4 || b[0] < 0 || b[1] < 0 || b[2] >= c.width || b[3] >= c.height) {
        throw std::out_of_range("a box of " + l.name + " is not inside the frame");
      }
      for (int v = b[1]; v <= b[3]; ++v) {
        for (int u = b[0]; u <= b[2]; ++u) {
          const size_t i = static_cast<size_t>(v) * c.width + u;
          if (std::isfinite(c.x[i])) l.pixels.push_back(i);
        }
      }
    }
    for (size_t i : l.pixels) {
      l.centroid += Eigen::Vector3d(c.x[i], c.y[i], c.z[i]) / static_cast<double>(l.pixels.size());
    }
    labels.push_back(l);
  }
  return labels;
}

LabelScore ScoreLabels(const std::vector<Label>& labels,
                       const std::vector<segmenter::DetectedPlane>& planes,
                       const std::vector<int32_t>& point_labels) {
  LabelScore score;
  score.labels = static_cast<int>(labels.size());
  score.detected = static_cast<int>(planes.size());
  std::vector<int> claimed(planes.size(), 0);
  for (const Label& l : labels) {
    std::map<int, int> held;
    for (size_t i : l.pixels) ++held[point_labels[i]];
    int best = -1, along = 0;
    for (const auto& [plane, count] : held) {
      if (plane < 0) continue;
      const segmenter::DetectedPlane& p = planes[static_cast<size_t>(plane)];
      if (count >= kSplitShare * l.pixels.size() && Along(p, l)) ++along;
      if (count >= kMostOfIt * l.pixels.size() && Along(p, l)) best = plane;
    }
    if (best >= 0) {
      const segmenter::DetectedPlane& p = planes[static_cast<size_t>(best)];
      ++score.found;
      ++claimed[static_cast<size_t>(best)];
      score.angles_deg.push_back(PlaneAngleDeg(p.normal.cast<double>(), l.normal));
      score.offsets_m.push_back(Offset(p, l));
    } else {
      score.missed.push_back(l.name);
    }
    if (along > 1) ++score.split;
  }
  for (size_t j = 0; j < planes.size(); ++j) {
    if (claimed[j] == 0) score.unmatched.push_back(static_cast<int>(j));
  }
  return score;
}

void Tally(const LabelScore& score, AccuracyTally* tally) {
  tally->AddFrame();
  tally->AddDetections(score.detected, score.detected - static_cast<int>(score.unmatched.size()));
  for (size_t i = 0; i < score.angles_deg.size(); ++i) {
    tally->AddRecalled(score.angles_deg[i], score.offsets_m[i]);
  }
  for (int i = score.found; i < score.labels; ++i) tally->AddMissed();
}

}  // namespace relplane::plane_truth
