#pragma once
// After EM: split each plane's support into connected pieces and describe each piece.

#include <cstdint>
#include <memory>
#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/em.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter {

// Buffers of DescribePieces kept between frames (grids, cells, per-point indices), so a
// long-lived segmenter does not allocate them per cloud. Not shared between threads.
class PieceWorkspace {
 public:
  PieceWorkspace();
  ~PieceWorkspace();
  PieceWorkspace(PieceWorkspace&&) noexcept;
  PieceWorkspace& operator=(PieceWorkspace&&) noexcept;
  struct Buffers;
  Buffers& Get() { return *buffers_; }

 private:
  std::unique_ptr<Buffers> buffers_;
};

// A mixture plane whose largest piece leaned between two faces and was fitted to the line most
// of its points lie on (DominantLineFit): the plane of that line, with the piece's RMS as its
// sigma. `plane` indexes the mixture planes passed to DescribePieces.
struct LineRefit {
  int plane = -1;
  EmPlane refit;
};

// How the sensor sampled the described cloud.
struct Sampling {
  // Radians between neighbouring samples, learnt from the cloud (EstimateAngularStep); 0:
  // unknown. For a subsampled cloud, the subsample's step.
  float angular_step = 0.0f;
  float ray_step = 0.0f;  // radians, the sensor's own angular step; 0: unknown
  float share = 1.0f;     // the described points' share of the sensor's samples (subsampled: < 1)
};

// What DescribePieces describes: a cloud whose points are labelled with the mixture planes.
struct DescribeRequest {
  const Cloud& cloud;
  const std::vector<int32_t>& labels;  // per point: its index into `planes`, -1 for none
  // Per point (from AssignPoints, may be empty): on the strip where two planes meet. Such points
  // belong to a piece but cannot connect pieces.
  const std::vector<uint8_t>& ambiguous;
  const std::vector<EmPlane>& planes;
  Sampling sampling;
  bool want_piece_labels = false;  // fill Description::piece_labels
};

// What DescribePieces finds.
struct Description {
  std::vector<DetectedPlane> planes;  // decreasing support
  // With DescribeRequest::want_piece_labels: per point, its index into `planes`, -1 for points
  // in no piece.
  std::vector<int32_t> piece_labels;
  std::vector<uint8_t> plane_has_piece;  // per mixture plane: whether it formed a kept piece
  std::vector<LineRefit> line_refits;    // the mixture planes whose piece was fitted to a line
};

// For every plane, the points labelled with it are binned into an occupancy grid in the
// plane's own coordinates (options.extents.cell_size); occupied cells within reach of one
// another form one piece, so two walls on one line with a door between them are two planes.
// The reach is options.extents.cell_reach cells, or more where the sensor's samples land
// further apart: a point at range r on a plane at distance d from the sensor has neighbours
// about r^2 * angular_step / d away (the incidence angle's cosine is d / r), and cells connect
// within options.extents.reach_spacings such spacings.
// Each piece with at least options.extents.min_points points is refitted by least squares and
// gets its centroid, RMS, support count and extent polygon (a rectangle aligned with the
// vertical for a vertical plane, the convex hull otherwise); its normal points towards the
// sensor at the origin. A vertical piece's ends along its wall are estimated from its points
// furthest out (EstimateEnd, wall_ends.hpp) when the sampling's ray_step is known.
// `workspace` (optional) keeps the buffers for the next call.
Description DescribePieces(const DescribeRequest& request, const Options& options,
                           PieceWorkspace* workspace = nullptr);

// DescribePieces in two halves, so a caller can see which mixture planes form a kept piece
// before paying for the description. FormPieces bins the points and finds the connected
// pieces, keeps them in `workspace` and returns Description::plane_has_piece;
// DescribeFormedPieces then describes those pieces for the same request, exactly as
// DescribePieces would.
std::vector<uint8_t> FormPieces(const DescribeRequest& request, const Options& options,
                                PieceWorkspace* workspace);
Description DescribeFormedPieces(const DescribeRequest& request, const Options& options,
                                 PieceWorkspace* workspace);

}  // namespace relplane::segmenter
