#pragma once
// Occupancy grids in the planes' own coordinates and their connected pieces (the first half of
// DescribePieces). Private to the library.

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <vector>

#include "grid_passes.hpp"
#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/em.hpp"
#include "relplane/segmenter/extent.hpp"
#include "relplane/segmenter/moments.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter {

constexpr float kInf = std::numeric_limits<float>::infinity();

struct Piece;  // piece_fit.hpp

// Per occupied cell, in a small array: how many points it holds and whether any of them is
// solid (not on the strip where two planes meet).
struct CellCount {
  int32_t count = 0;
  int32_t solid = 0;  // 1 or 0
};

// Per occupied cell, in one cache line, what binning touches for the points that enter the fits
// (one in FitStride): their moments and the range of their distances to the EM plane.
struct alignas(64) CellMoments {
  LocalMoments all;
  float e_lo = kInf, e_hi = -kInf;
};

// Per occupied cell, second pass: the moments of its points beyond the trim of the piece's first
// fit (about the cell's reference point), and the extreme points along the piece's own axes
// (for a cell on the piece's boundary).
struct CellFinish {
  LocalMoments beyond;
  Eigen::Vector2f lo_a{kInf, 0}, hi_a{-kInf, 0}, lo_b{0, kInf}, hi_b{0, -kInf};
};

// One EM plane's grid: origin at its centroid, axes u (horizontal for a vertical plane), v.
struct PlaneGrid {
  bool used = false;  // enough points to make a piece
  int points = 0;
  Eigen::Vector3f origin = Eigen::Vector3f::Zero(), n = Eigen::Vector3f::UnitZ(),
                  u = Eigen::Vector3f::UnitX(), v = Eigen::Vector3f::UnitY();
  float a_lo = kInf, a_hi = -kInf, b_lo = kInf, b_hi = -kInf;
  float cell = 0.1f;
  float inv_cell = 10.0f;
  int w = 0, h = 0;
  size_t base = 0;  // offset of its slots in Buffers::slot_of
};

struct PieceWorkspace::Buffers {
  std::vector<float> a, b;                    // per point: coordinates in its plane's grid
  std::vector<float> e;                       // per point: its distance to its EM plane
  std::vector<int32_t> cell_of_point;         // per point: its cell, -1 for none
  std::vector<int32_t> slot_of;               // per grid slot (all grids): its cell, -1 if empty
  std::vector<Cell> cells;                    // in order of first appearance
  std::vector<CellCount> counts;              // per cell
  std::vector<int32_t> lane_count;            // per cell and lane: its points, while binning
  std::vector<CellMoments> moments;           // per cell
  std::vector<int32_t> fit_start;             // per cell and one more: where its points start in
  std::vector<int32_t> fit_order;             // the indices of the points that enter the fits
  std::vector<CellFinish> finish;             // per cell
  std::vector<uint8_t> mode;                  // per cell: what the second pass does with its points
  std::vector<PlaneGrid> grids;               // per EM plane
  PlaneTable table;                           // the grids, for the per-point passes
  std::vector<int32_t> piece_of;              // per cell: its piece, -1 for none
  std::vector<int32_t> parent, root_piece;    // union-find over cells
  std::vector<int32_t> reach;                 // per cell, in cells; 0 for cells in no piece
  std::vector<uint8_t> outer;                 // per cell: first or last of its piece on a line
  std::vector<int32_t> piece_point_start;     // per piece and one more: where its points start in
  std::vector<Eigen::Vector3f> piece_points;  // a vertical piece's fitted points, about its fit
  std::vector<Piece> pieces;                  // FormPieces' pieces, for DescribeFormedPieces
};

// In-plane axes: for a vertical plane u is horizontal and v points up, so the extent rectangle
// follows the wall's vertical edges; otherwise any orthonormal pair.
void PlaneAxes(const Eigen::Vector3f& n, bool vertical, Eigen::Vector3f* u, Eigen::Vector3f* v);

// Points of a cloud of n points that enter the fits: one in FitStride (see
// DescriptionOptions::fit_points_max).
size_t FitStride(size_t n, const Options& options);

// Bins the points of every plane with at least options.extents.min_points labelled points into that
// plane's grid (coarsened until it has at most options.extents.max_cells cells): fills grids, cells
// (count, whether it holds a solid point, moments of the points that enter the fits) and
// cell_of_point.
void BinPoints(const Cloud& cloud, const std::vector<int32_t>& labels,
               const std::vector<uint8_t>& ambiguous, const std::vector<EmPlane>& planes,
               const Options& options, PieceWorkspace::Buffers* w);

// Connected components of the solid cells of each grid: two cells connect when each lies
// within the other's reach (cell_reach, or more where samples are further apart, see
// DescribePieces). Cells holding only points on the strip where two planes meet belong to no
// piece: along a floor, that strip would otherwise bridge the door between two walls. Fills
// piece_of, numbering pieces in order of their cells' first appearance; returns their count.
int LabelPieces(const std::vector<EmPlane>& planes, const Options& options, float angular_step,
                PieceWorkspace::Buffers* w);

// Marks in `outer` the cells that are the first or last of their piece along their grid row or
// grid column. Only their points can shape the piece's extent, to within a cell: any other cell
// lies between two marked cells of its row and two of its column.
void MarkOuterCells(int num_pieces, PieceWorkspace::Buffers* w);

}  // namespace relplane::segmenter
