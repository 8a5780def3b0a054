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

// For every plane, the points labelled with it are binned into an occupancy grid in the
// plane's own coordinates (options.cell_size); occupied cells within reach of one another form
// one piece, so two walls on one line with a door between them are two planes. The reach is
// options.cell_reach cells, or more where the sensor's samples land further apart: a point at
// range r on a plane at distance d from the sensor has neighbours about r^2 * angular_step / d
// away (the incidence angle's cosine is d / r), and cells connect within
// options.reach_spacings such spacings. `angular_step` (radians, from EstimateAngularStep; 0:
// unknown) is learnt from the cloud, not from intrinsics.
// Each piece with at least options.min_points points is refitted by least squares and gets its
// centroid, RMS, support count and extent polygon (a rectangle aligned with the vertical for a
// vertical plane, the convex hull otherwise); its normal points towards the sensor at the
// origin. Pieces come back in order of decreasing support.
// A vertical piece's ends along its wall are estimated from its points furthest out
// (EstimateEnd, wall_ends.hpp) when options.wall_end_estimate is set and `ray_step` (the
// sensor's own angular step, radians) is known; `share` is the described points' share of the
// sensor's samples (a subsampled cloud: below 1). `plane_has_piece` (optional) receives, for
// each of `planes`, whether it formed a kept piece.
// `ambiguous` (from AssignPoints, may be empty) marks points on the strip where two planes
// meet: they belong to a piece but cannot connect pieces. `piece_labels` (optional) receives
// each point's index into the result, -1 for points in no piece. `workspace` (optional) keeps
// the buffers for the next call. `line_refits` (optional) receives the mixture planes whose
// piece was fitted to a line (LineRefit).
std::vector<DetectedPlane> DescribePieces(
    const Cloud& cloud, const std::vector<int32_t>& labels, const std::vector<uint8_t>& ambiguous,
    const std::vector<EmPlane>& planes, const Options& options, float angular_step = 0.0f,
    float ray_step = 0.0f, float share = 1.0f, std::vector<int32_t>* piece_labels = nullptr,
    PieceWorkspace* workspace = nullptr, std::vector<uint8_t>* plane_has_piece = nullptr,
    std::vector<LineRefit>* line_refits = nullptr);

}  // namespace relplane::segmenter
