#pragma once
// The per-point passes of binning (BinPoints, piece_grid.hpp): each point's coordinates in its
// plane's grid, each plane's bounds there, each point's grid slot. Private to the library.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace relplane::segmenter {

// Per occupied cell: where it is.
struct Cell {
  int32_t plane = 0;
  int ix = 0, iy = 0;
};

// The planes' grid frames in arrays indexed by a point's label plus one: entry 0 (unlabelled
// points) and the padding have no grid. The passes look a point's plane up without a branch.
struct PlaneTable {
  // Per grid: x, y, z of its origin (0-2), axes u (3-5) and v (6-8) and normal n (9-11).
  std::vector<float> frame[12];
  // Per grid: lower bounds, inverse cell size, last column and row, width, and the offset of
  // its slots (-1: no grid).
  std::vector<float> a_lo, b_lo, inv_cell;
  std::vector<int32_t> w1, h1, w, base;
  // Per grid: its cell size, and the distance of its plane from the sensor (for the reach).
  std::vector<float> cell, distance;

  // Room for `planes` planes and the unlabelled entry, padded to whole chunks of 8 entries;
  // every entry cleared (no grid).
  void Reset(size_t planes);
};

// Bounds of one plane's points in its grid, and their count.
struct GridBounds {
  int points = 0;
  float a_lo = std::numeric_limits<float>::infinity();
  float a_hi = -std::numeric_limits<float>::infinity();
  float b_lo = std::numeric_limits<float>::infinity();
  float b_hi = -std::numeric_limits<float>::infinity();
};

// Each point's coordinates (a, b) in its plane's grid and its distance e to the plane:
// q = p - origin, a = u . q, b = v . q, e = n . q. Unlabelled points get values no one reads.
void ProjectToGrids(size_t n, const float* x, const float* y, const float* z, const int32_t* label,
                    const PlaneTable& table, float* a, float* b, float* e);

// The bounds in its grid of the points labelled `plane`.
GridBounds PlaneBounds(size_t n, const int32_t* label, int32_t plane, const float* a,
                       const float* b);

// Each point's slot in its plane's grid (base + row * width + column, the column and row
// clamped to the grid), -1 for a point with no grid.
void GridSlots(size_t n, const int32_t* label, const float* a, const float* b,
               const PlaneTable& table, int32_t* slot);

// What sets a cell's reach (see ExtentOptions::cell_reach, reach_spacings, max_reach).
struct ReachRule {
  int cell_reach = 2;           // cells, at least
  float reach_spacings = 0.0f;  // > 0
  float max_reach = 0.0f;       // metres
  float angular_step = 0.0f;    // radians, > 0
};

// Each cell's reach in cells: the rule's reach_spacings expected sample spacings
// (SampleSpacing) at the range of the cell's centre, at most max_reach, rounded up to whole
// cells and at least cell_reach.
void CellReach(const std::vector<Cell>& cells, const PlaneTable& table, const ReachRule& rule,
               int32_t* reach);

}  // namespace relplane::segmenter
