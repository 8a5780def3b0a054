#pragma once
// The EM plane segmenter: one cloud in, its planes out (DESIGN.md: relplane-segmenter), the
// paper's input stage (§I, §III: 2½D planes from a 3D point field by EM, after Thrun et al.).

#include <cstdint>
#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/em.hpp"
#include "relplane/segmenter/extent.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter {

struct Result {
  std::vector<DetectedPlane> planes;  // decreasing support
  int64_t input_points = 0;
  int64_t dropped_nonfinite = 0;  // NaN/inf points left out
  int64_t assigned_points = 0;    // points supporting some EM plane before the split
  int em_planes = 0;              // mixture components after EM (and pieceless ones dropped)
  int pieceless_planes = 0;       // mixture components dropped for having no piece
  int layer_planes = 0;           // mixture components dropped as quantization layers
  int grazing_planes = 0;         // mixture components dropped as beyond the camera's incidence
  int line_refits = 0;            // mixture planes set to their piece's line (DominantLineFit)
  int rounds = 0;                 // EM rounds run
  int reanchored = 0;             // seeds lost to the sensor's motion and kept, moved with it
  float angular_step = 0.0f;      // radians, the sensor's sampling step learnt from the cloud
  // With options.keep_labels: for every input point, its index in `planes` or -1.
  std::vector<int32_t> labels;
};

// Segments a stream of clouds. Each frame is seeded with the previous frame's planes (the
// paper's input is continuous, §IV), so a steady scene needs fewer rounds and no new proposals.
class Segmenter {
 public:
  explicit Segmenter(Options options = {});

  Result Segment(const Cloud& cloud);
  // Forgets the previous frame: the next cloud is segmented from proposals alone.
  void Reset() { previous_.clear(); }
  const Options& GetOptions() const { return options_; }
  // The mixture's planes after the last frame (the seeds of the next one).
  const std::vector<EmPlane>& MixturePlanes() const { return previous_; }

 private:
  Options options_;
  std::vector<EmPlane> previous_;
  // Buffers reused from frame to frame (the segmenter is long-lived): no per-cloud allocation.
  Cloud finite_, sample_, described_;
  Responsibilities resp_;
  std::vector<int32_t> labels_;
  std::vector<uint8_t> ambiguous_;
  PieceWorkspace workspace_;
};

}  // namespace relplane::segmenter
