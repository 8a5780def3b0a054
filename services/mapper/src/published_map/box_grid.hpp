#pragma once
// A uniform grid over 2D boxes: the walls near a point or box without looking at every pair
// (the published map's clean-up and corner snapping ran over every pair of walls: 140 ms for a
// 2,000-wall map).

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace relplane::mapper {

class BoxGrid {
 public:
  explicit BoxGrid(double cell) : cell_(cell) {}

  void Insert(size_t id, const Eigen::AlignedBox2d& box) {
    if (Cells(box) > kMaxCells) {
      wide_.push_back(id);  // met by every query
      return;
    }
    ForCells(box, [&](int64_t key) { cells_[key].push_back(id); });
  }

  // The ids whose boxes may overlap `box` (a superset), each once, in increasing order: a scan
  // over them meets the walls in the same order as a scan over all of them.
  std::vector<size_t> Query(const Eigen::AlignedBox2d& box) const {
    std::vector<size_t> ids = wide_;
    if (Cells(box) > kMaxCells) {  // as wide as the map: every wall
      for (const auto& [key, cell] : cells_) ids.insert(ids.end(), cell.begin(), cell.end());
    } else {
      ForCells(box, [&](int64_t key) {
        auto it = cells_.find(key);
        if (it != cells_.end()) ids.insert(ids.end(), it->second.begin(), it->second.end());
      });
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
  }

 private:
  template <typename F>
  void ForCells(const Eigen::AlignedBox2d& box, F&& f) const {
    const int64_t x0 = Cell(box.min().x()), x1 = Cell(box.max().x());
    const int64_t y0 = Cell(box.min().y()), y1 = Cell(box.max().y());
    for (int64_t x = x0; x <= x1; ++x) {
      for (int64_t y = y0; y <= y1; ++y) f(x * 2000003 + y);
    }
  }
  int64_t Cell(double v) const { return static_cast<int64_t>(std::floor(v / cell_)); }
  // Cells a box covers (a NaN box counts as too many).
  double Cells(const Eigen::AlignedBox2d& box) const {
    const double n = (std::floor(box.max().x() / cell_) - std::floor(box.min().x() / cell_) + 1) *
                     (std::floor(box.max().y() / cell_) - std::floor(box.min().y() / cell_) + 1);
    return std::isfinite(n) ? n : kMaxCells + 1;
  }

  static constexpr double kMaxCells = 1e5;

  double cell_;
  std::unordered_map<int64_t, std::vector<size_t>> cells_;
  std::vector<size_t> wide_;
};

}  // namespace relplane::mapper
