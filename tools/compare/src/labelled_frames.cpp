#include "relplane/compare/labelled_frames.hpp"

#include <algorithm>
#include <exception>
#include <filesystem>

namespace relplane::compare {

std::vector<LabelledFrame> LoadLabelledFrames(const std::string& frames_dir,
                                              const std::string& labels_dir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(labels_dir)) throw std::runtime_error("no labels folder " + labels_dir);
  if (!fs::is_directory(frames_dir)) throw std::runtime_error("no frames folder " + frames_dir);
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(labels_dir)) {
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) throw std::runtime_error("no labels (*.json) in " + labels_dir);
  std::vector<LabelledFrame> frames;
  for (const fs::path& labels : files) {
    LabelledFrame frame;
    frame.name = labels.stem().string();
    const fs::path pcd = fs::path(frames_dir) / (frame.name + ".pcd");
    if (!fs::exists(pcd)) {
      throw std::runtime_error("no frame " + pcd.string() + " for labels " + labels.string());
    }
    frame.cloud = pcd::ReadPcd(pcd.string());  // PcdError is a runtime_error: one line
    if (frame.cloud.height < 2) throw std::runtime_error(pcd.string() + " is not organized");
    pcd::OpticalToSensor(&frame.cloud);
    try {
      frame.labels = plane_truth::LoadLabels(labels.string(), frame.cloud);
    } catch (const std::exception& e) {
      throw std::runtime_error(labels.string() + ": " + e.what());
    }
    frames.push_back(std::move(frame));
  }
  return frames;
}

}  // namespace relplane::compare
