#include "relplane/segmenter/segmenter.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <utility>

#include "relplane/segmenter/assign.hpp"
#include "relplane/segmenter/extent.hpp"
#include "relplane/segmenter/proposals.hpp"
#include "relplane/segmenter/spacing.hpp"
#include "seed_motion.hpp"

namespace relplane::segmenter {
namespace {

// NaN and inf have all exponent bits set: adding one to the masked exponent carries into the
// sign bit for them alone, so or-ing those sums tells, in one branch-free pass of and, add and
// or that vectorises on any x86-64.
bool AllFinite(const std::vector<float>& v) {
  constexpr uint32_t kExponent = 0x7f800000u, kExponentOne = 0x00800000u;
  uint32_t any = 0;
  for (float f : v) {
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    any |= (bits & kExponent) + kExponentOne;
  }
  return (any & 0x80000000u) == 0;
}

bool AllFinite(const Cloud& in) { return AllFinite(in.x) && AllFinite(in.y) && AllFinite(in.z); }

// Keeps the finite points only; `out`'s buffers are reused.
void FiniteOnly(const Cloud& in, Cloud* out) {
  out->x.clear();
  out->y.clear();
  out->z.clear();
  out->Reserve(in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    if (std::isfinite(in.x[i]) && std::isfinite(in.y[i]) && std::isfinite(in.z[i])) {
      out->Add(in.x[i], in.y[i], in.z[i]);
    }
  }
}

// Stratified subsample of at most `count` points: one point at a jittered position in each of
// `count` equal strides, so no lattice aliases with the row layout of an organized cloud.
void Subsample(const Cloud& in, int count, uint32_t seed, Cloud* sample) {
  Cloud& out = *sample;
  out.x.clear();
  out.y.clear();
  out.z.clear();
  if (static_cast<int>(in.size()) <= count) {
    out = in;
    return;
  }
  out.x.resize(count);
  out.y.resize(count);
  out.z.resize(count);
  const double stride = static_cast<double>(in.size()) / count;
  uint32_t state = seed * 747796405u + 2891336453u;
  for (int k = 0; k < count; ++k) {
    state = state * 1664525u + 1013904223u;  // LCG: fixed sequence, cheap
    const double jitter = (state >> 8) * (1.0 / 16777216.0);
    const size_t i = std::min(in.size() - 1, static_cast<size_t>((k + jitter) * stride));
    out.x[k] = in.x[i];
    out.y[k] = in.y[i];
    out.z[k] = in.z[i];
  }
}

std::vector<int> Unexplained(const Responsibilities& resp) {
  std::vector<int> idx;
  for (int i = 0; i < resp.num_points; ++i) {
    if (resp.Outlier(i) > 0.5f) idx.push_back(i);
  }
  return idx;
}

// Merges near-identical planes (the one with less support goes) and prunes weak ones.
// Returns true when any plane was removed.
bool MergeAndPrune(const Options& options, float min_support, std::vector<EmPlane>* planes) {
  std::vector<EmPlane>& p = *planes;
  std::stable_sort(p.begin(), p.end(),
                   [](const EmPlane& a, const EmPlane& b) { return a.support > b.support; });
  const float cos_merge = std::cos(options.merge.angle_deg * static_cast<float>(M_PI) / 180.0f);
  std::vector<bool> gone(p.size(), false);
  for (size_t i = 0; i < p.size(); ++i) {
    if (p[i].support < min_support) gone[i] = true;
    if (gone[i]) continue;
    for (size_t j = i + 1; j < p.size(); ++j) {
      if (gone[j]) continue;
      const bool parallel = std::fabs(p[i].normal.dot(p[j].normal)) > cos_merge;
      const float within = options.sensor.CoplanarDistance(
          options.merge.distance, p[i].normal, p[i].centroid, p[j].normal, p[j].centroid);
      const bool coplanar = std::fabs(p[i].normal.dot(p[j].centroid) + p[i].d) < within &&
                            std::fabs(p[j].normal.dot(p[i].centroid) + p[j].d) < within;
      if (parallel && coplanar) gone[j] = true;
    }
  }
  std::vector<EmPlane> kept;
  for (size_t i = 0; i < p.size(); ++i) {
    if (!gone[i]) kept.push_back(p[i]);
  }
  const bool changed = kept.size() != p.size();
  p.swap(kept);
  return changed;
}

// What a detection is when the camera could not have returned it as a surface.
enum class NoSurface { kSurface, kLayer, kGrazing };

// Flatter than the camera resolves along its normal at its centroid (the points of one quantized
// depth, SensorOptions::layer_rms_share), or facing its rays beyond the camera's incidence
// limit (samples of another surface spread along their rays, SensorOptions::BeyondIncidence).
NoSurface Classify(const SensorOptions& sensor, const DetectedPlane& p) {
  if (p.rms < sensor.layer_rms_share * sensor.SigmaAlongNormal(p.normal, p.centroid)) {
    return NoSurface::kLayer;
  }
  if (sensor.BeyondIncidence(p.normal, p.centroid)) return NoSurface::kGrazing;
  return NoSurface::kSurface;
}

struct Dropped {
  int layers = 0;
  int grazing = 0;
  int Total() const { return layers + grazing; }
};

// Removes from `mixture` the planes of the detections that are no surface (Classify); returns
// how many of each kind.
Dropped DropNoSurfaces(const SensorOptions& sensor, const std::vector<DetectedPlane>& detected,
                       std::vector<EmPlane>* mixture) {
  const float cos_same = std::cos(2.0f * static_cast<float>(M_PI) / 180.0f);
  std::vector<NoSurface> kind(mixture->size(), NoSurface::kSurface);
  for (const DetectedPlane& p : detected) {
    const NoSurface k = Classify(sensor, p);
    if (k == NoSurface::kSurface) continue;
    // Its mixture plane: the one through its centroid, facing the same way.
    int best = -1;
    float best_offset = std::numeric_limits<float>::infinity();
    for (size_t j = 0; j < mixture->size(); ++j) {
      const EmPlane& m = (*mixture)[j];
      const float offset = std::fabs(m.normal.dot(p.centroid) + m.d);
      if (std::fabs(m.normal.dot(p.normal)) > cos_same && offset < best_offset) {
        best = static_cast<int>(j);
        best_offset = offset;
      }
    }
    if (best >= 0) kind[static_cast<size_t>(best)] = k;
  }
  Dropped dropped;
  std::vector<EmPlane> kept;
  for (size_t j = 0; j < mixture->size(); ++j) {
    if (kind[j] == NoSurface::kSurface) kept.push_back((*mixture)[j]);
    dropped.layers += kind[j] == NoSurface::kLayer;
    dropped.grazing += kind[j] == NoSurface::kGrazing;
  }
  mixture->swap(kept);
  return dropped;
}

}  // namespace

namespace {

// With a known camera a plane's own noise is what remains on top of the camera's.
Options WithSensor(Options options) {
  if (options.sensor.Known()) {
    options.noise.sigma_max =
        std::max(options.noise.sigma_min,
                 std::min(options.noise.sigma_max, options.sensor.surface_sigma_max));
    options.noise.sigma_initial = std::min(options.noise.sigma_initial, options.noise.sigma_max);
  }
  return options;
}

}  // namespace

Segmenter::Segmenter(Options options) : options_(WithSensor(options)) {}

Result Segmenter::Segment(const Cloud& input) {
  Result result;
  result.input_points = static_cast<int64_t>(input.size());
  const bool all_finite = AllFinite(input);
  if (!all_finite) FiniteOnly(input, &finite_);
  const Cloud& cloud = all_finite ? input : finite_;
  result.dropped_nonfinite = result.input_points - static_cast<int64_t>(cloud.size());
  if (cloud.empty()) {
    previous_.clear();
    return result;
  }

  // EM on a subsample; support thresholds scale with the sampling ratio.
  const int em_points =
      std::clamp(static_cast<int>(cloud.size() / std::max(1, options_.em.fraction)),
                 options_.em.points_min, std::max(options_.em.points_min, options_.em.points_max));
  Subsample(cloud, em_points, options_.seed, &sample_);
  const Cloud& sample = sample_;
  const float ratio = static_cast<float>(sample.size()) / static_cast<float>(cloud.size());
  const int min_support =
      std::max(options_.em.min_support,
               static_cast<int>(std::ceil(options_.extents.min_points * ratio * 0.5f)));
  std::mt19937 rng(options_.seed);
  std::vector<EmPlane> planes = previous_;
  Responsibilities& resp = resp_;
  for (int round = 0; round < options_.em.max_rounds; ++round) {
    result.rounds = round + 1;
    RunEm(sample, options_, options_.em.iterations, &planes, &resp);
    if (round == 0) {
      result.reanchored = CarryLostSeeds(sample, options_, previous_,
                                         static_cast<float>(min_support), &planes, &resp);
    }
    // Pruning and merging change the mixture: let EM settle the survivors before proposing.
    if (MergeAndPrune(options_, static_cast<float>(min_support), &planes)) {
      RunEm(sample, options_, options_.em.iterations, &planes, &resp);
    }
    const int room = options_.em.max_planes - static_cast<int>(planes.size());
    if (room <= 0) break;
    Options propose = options_;
    propose.proposals.max_per_round = std::min(room, options_.proposals.max_per_round);
    const auto proposals = ProposePlanes(sample, Unexplained(resp), propose, min_support, &rng);
    if (proposals.empty()) break;
    planes.insert(planes.end(), proposals.begin(), proposals.end());
    if (round + 1 == options_.em.max_rounds) {  // out of rounds: still fit the last proposals
      RunEm(sample, options_, options_.em.iterations, &planes, &resp);
    }
  }
  MergeAndPrune(options_, static_cast<float>(min_support), &planes);
  previous_ = planes;
  result.em_planes = static_cast<int>(planes.size());

  // One hard assignment pass, then connected pieces and their extents, over every point or, for
  // a large cloud, over a stratified subsample of description.points_max points (support counts
  // scaled back). The sensor's angular step, learnt from the EM sample, sets how far apart the
  // described points land on each plane: far, grazing parts of a wall stay connected.
  const bool subsample = !options_.keep_labels && options_.description.points_max > 0 &&
                         cloud.size() > static_cast<size_t>(options_.description.points_max);
  if (subsample) Subsample(cloud, options_.description.points_max, options_.seed + 1, &described_);
  const Cloud& described = subsample ? described_ : cloud;
  const double scale = static_cast<double>(cloud.size()) / static_cast<double>(described.size());
  Options describe = options_;
  describe.extents.min_points =
      std::max(1, static_cast<int>(std::ceil(options_.extents.min_points / scale - 1e-9)));
  result.angular_step = EstimateAngularStep(sample, described.size());
  // The subsample keeps every ray's direction, only fewer of them: the sensor's own step.
  const float ray_step = result.angular_step / static_cast<float>(std::sqrt(scale));
  const float share = options_.keep_labels ? 1.0f : static_cast<float>(1.0 / scale);
  const Cloud& assigned_cloud = options_.keep_labels ? cloud : described;
  const Options& describe_options = options_.keep_labels ? options_ : describe;
  Description description;
  const auto request = [&] {
    return DescribeRequest{assigned_cloud,
                           labels_,
                           ambiguous_,
                           planes,
                           Sampling{result.angular_step, ray_step, share},
                           options_.keep_labels};
  };
  const auto form = [&] {
    AssignPoints(assigned_cloud, planes, options_, &labels_, &ambiguous_);
    return FormPieces(request(), describe_options, &workspace_);
  };
  const auto describe_formed = [&] {
    description = DescribeFormedPieces(request(), describe_options, &workspace_);
    result.planes = std::move(description.planes);
  };
  const auto describe_all = [&] {
    form();
    describe_formed();
  };
  // A mixture plane with no piece of its own is no surface (on a level sensor's noise-free
  // frames a row of floor samples, one of ceiling samples and a wall's column at the same depth
  // lie exactly in one plane square to the view), yet it claims the points where it crosses a
  // wall as ambiguous (AssignPoints), and those cannot connect a piece: the wall's piece is cut
  // short. Such planes are found once the pieces are formed, before they are described, and the
  // frame is assigned again without them. They stay in the mixture the next frame starts from: a
  // wall coming into view has no piece yet (docs/decisions/segmenter.md).
  const std::vector<uint8_t> has_piece = form();
  if (std::find(has_piece.begin(), has_piece.end(), 0) != has_piece.end()) {
    std::vector<EmPlane> surfaces;
    for (size_t j = 0; j < planes.size(); ++j) {
      if (has_piece[j]) surfaces.push_back(planes[j]);
    }
    result.pieceless_planes = static_cast<int>(planes.size() - surfaces.size());
    planes = std::move(surfaces);
    result.em_planes = static_cast<int>(planes.size());
    form();
  }
  describe_formed();
  // A plane flatter than the camera resolves at its range is no surface but the points of one
  // quantized depth value: a tilted surface at range is a staircase of exactly flat layers, and
  // each fits a plane with an RMS near zero. Nor is a plane the camera's rays graze beyond the
  // incidence it returns depth from: a narrow strip of a far wall, spread along its rays by the
  // depth noise, fits a plane that contains those rays. Its mixture plane goes and the frame is
  // assigned and described again, so its points return to the surface they sample.
  if (options_.sensor.Known()) {
    const Dropped dropped = DropNoSurfaces(options_.sensor, result.planes, &planes);
    if (dropped.Total() > 0) {
      DropNoSurfaces(options_.sensor, result.planes, &previous_);
      result.layer_planes = dropped.layers;
      result.grazing_planes = dropped.grazing;
      result.em_planes = static_cast<int>(planes.size());
      describe_all();
    }
  }
  // A mixture plane that leans between two faces at a convex corner (a grazing pilaster front
  // and the side it meets) holds the side's samples near the corner: its piece's line fit
  // (DominantLineFit) leaves them out of the fit but not out of the piece, which reaches past
  // the corner, and the side's piece ends short of it. The frame is assigned and described
  // again with those planes set to their lines, once; the next frame's mixture starts from the
  // lines too.
  if (!description.line_refits.empty()) {
    const std::vector<LineRefit> line_refits = std::move(description.line_refits);
    for (const LineRefit& r : line_refits) {
      const EmPlane& was = planes[static_cast<size_t>(r.plane)];
      for (EmPlane& carried : previous_) {
        if (carried.normal == was.normal && carried.d == was.d) carried = r.refit;
      }
      planes[static_cast<size_t>(r.plane)] = r.refit;
    }
    result.line_refits = static_cast<int>(line_refits.size());
    describe_all();
  }
  if (options_.sensor.Known()) {
    // A plane that is no surface may remain where its mixture plane holds nothing else (a wall
    // just beyond the camera's range, of which only its nearest depth value comes back): not
    // reported.
    // Each plane's new index, -1 for one that goes; labels index the planes, so the dropped
    // planes' points become unlabelled.
    std::vector<int32_t> renumber(result.planes.size(), -1);
    std::vector<DetectedPlane> kept;
    for (size_t j = 0; j < result.planes.size(); ++j) {
      const NoSurface k = Classify(options_.sensor, result.planes[j]);
      result.layer_planes += k == NoSurface::kLayer;
      result.grazing_planes += k == NoSurface::kGrazing;
      if (k != NoSurface::kSurface) continue;
      renumber[j] = static_cast<int32_t>(kept.size());
      kept.push_back(std::move(result.planes[j]));
    }
    if (kept.size() != result.planes.size() && options_.keep_labels) {
      for (int32_t& l : description.piece_labels) {
        if (l >= 0) l = renumber[static_cast<size_t>(l)];
      }
    }
    result.planes = std::move(kept);
  }
  const auto assigned =
      std::count_if(labels_.begin(), labels_.end(), [](int32_t l) { return l >= 0; });
  result.assigned_points = static_cast<int64_t>(assigned * scale);  // rounded down
  if (!options_.keep_labels) {
    if (subsample) {
      for (DetectedPlane& p : result.planes) {
        // Rounded down, as the assigned count is: the pieces never add up to more.
        p.num_points = static_cast<decltype(p.num_points)>(p.num_points * scale);
      }
    }
    return result;
  }
  // Back to the input's indexing: the non-finite points were left out of `cloud`.
  result.labels.assign(input.size(), -1);
  for (size_t i = 0, k = 0; i < input.size(); ++i) {
    if (std::isfinite(input.x[i]) && std::isfinite(input.y[i]) && std::isfinite(input.z[i])) {
      result.labels[i] = description.piece_labels[k++];
    }
  }
  return result;
}

}  // namespace relplane::segmenter
