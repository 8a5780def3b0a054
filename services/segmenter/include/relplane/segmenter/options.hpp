#pragma once
// Options of the EM plane segmenter, one struct per concern. Defaults work for depth sensors
// with noise up to sigma = 2 cm along the normal; the service fills them from the scenario's
// `segmenter` section, one YAML mapping per struct (options_yaml.cpp).

#include <cstdint>

#include "relplane/segmenter/sensor.hpp"

namespace relplane::segmenter {

// The E-step's noise model (`segmenter.noise`). Each plane learns its own noise sigma (the
// weighted RMS of its support), kept in [sigma_min, sigma_max]; sigma_min keeps noise-free
// clouds well conditioned.
struct NoiseOptions {
  float sigma_min = 0.003f;     // metres
  float sigma_max = 0.025f;     // metres
  float sigma_initial = 0.01f;  // metres, a new proposal's sigma before EM learns it
  // Depth sensors get noisier with range: a point at range r has variance
  // sigma^2 + (range_noise * r^2)^2 along the normal. 0 for noise constant with range (the
  // simulator); about 0.003 for a Kinect-type camera.
  float range_noise = 0.0f;  // 1/m
  // Density of the outlier class along a plane normal, 1/m: a point is an outlier when every
  // plane's Gaussian density is below this (about 2.5 sigma away for sigma = 2 cm).
  float outlier_density = 1.0f;
};

// EM on a subsample (`segmenter.em`): cloud_size / fraction points, clamped to
// [points_min, points_max] (a 640x480 cloud: 5000 points; 160x120: 2000).
struct EmOptions {
  int points_min = 2000;
  int points_max = 5000;
  int fraction = 60;
  int iterations = 8;              // E/M iterations per round (fewer once converged)
  int max_rounds = 6;              // rounds of EM + add/merge/prune
  int max_planes = 24;             // mixture components at most
  float converged_angle = 1e-4f;   // radians: a plane moving less has converged
  float converged_offset = 1e-4f;  // metres
  int min_support = 12;            // EM support (sum of responsibilities) below this is pruned
};

// New mixture components from the points no plane explains (`segmenter.proposals`).
struct ProposalOptions {
  int trials = 40;        // local neighbourhoods tried per proposal
  int neighbours = 30;    // a trial fits the seed point's nearest unexplained points
  float radius = 0.5f;    // metres, at most this far from the seed
  float max_rms = 0.03f;  // metres, a neighbourhood flatter than this may seed a plane
  int max_per_round = 4;
  int min_neighbours = 8;  // a trial needs at least this many unexplained points within radius
  // A neighbourhood whose scatter's smallest eigenvalue is over this share of its middle one is
  // not flat (30 neighbours on a flat patch with sigma = 2 cm give about 0.04; a patch across a
  // right-angled edge about 0.25).
  double max_flatness = 0.1;
  float inlier_sigmas = 2.5f;  // a proposal's inliers lie within this many of its sigma
};

// When two planes or two pieces are one surface (`segmenter.merge`).
struct MergeOptions {
  float angle_deg = 3.0f;  // near-identical planes: normals within this angle ...
  float distance = 0.04f;  // ... and each centroid this close to the other plane
  // Touching pieces are one surface when their normals are within this angle (and both
  // centroids within `distance`): a depth camera's few-degree bend at the image edge stays
  // part of the floor.
  float piece_angle_deg = 6.0f;
  // Vertical pieces lying over each other along and up the wall, over most of the smaller one,
  // each centroid within `distance` of the other's plane, are one surface when their normals
  // are within this angle: a depth sensor cannot see two surfaces there, so EM splitting one
  // face between two planes is undone.
  float overlap_angle_deg = 20.0f;
};

// Planes seeded from the previous frame and carried by the sensor's motion when EM loses them
// (`segmenter.seeds`).
struct SeedOptions {
  // A carried seed stays only if it finds at least this share of the support it had in the
  // previous frame.
  float kept_support = 0.5f;
  // Normal motion between frames (a robot at 1.5 m/s and 90 degrees/s at 30 Hz moves 5 cm and 3
  // degrees): beyond these the fits the motion came from may have jumped to other surfaces,
  // and seeds are not carried.
  float max_turn_deg = 5.0f;
  float max_shift = 0.2f;  // metres
};

// The hard assignment of every point after EM (`segmenter.assignment`).
struct AssignmentOptions {
  float inlier_sigmas = 3.0f;  // a point supports its nearest plane within this many sigma
  // Two planes whose normals differ by more than this meet in a line (a corner, not a step).
  float crossing_angle_deg = 20.0f;
};

// Connected pieces of each plane's support and their extents (`segmenter.extents`).
struct ExtentOptions {
  int min_points = 150;    // pieces with fewer supporting points are dropped
  float cell_size = 0.1f;  // metres, occupancy grid in the plane for connected pieces
  int cell_reach = 2;      // cells: occupied cells this close are connected, at least
  // Further where the samples land further apart (far away, grazing incidence): cells connect
  // within this many expected sample spacings (learnt from the cloud; 0: cell_reach only) ...
  float reach_spacings = 1.5f;
  float max_reach = 1.5f;        // ... but never beyond this, metres
  int max_cells = 250000;        // the grid coarsens beyond this many cells per plane
  float vertical_max_nz = 0.1f;  // |normal.z| below this is a vertical plane: rectangle extent
  float trim_sigmas =
      2.5f;             // a piece's final fit uses its points within this many RMS of the first
  int max_refits = 10;  // a vertical piece's trimmed fit is refitted at most this many more times
  // metres: a spacing of more than this at a wall's end is a view so grazing that few of the
  // wall's samples are near the end: the end moves out by at most half of it.
  float max_end_spacing = 0.3f;
  // An end this close to the cloud's furthest point, as a share of its range, is a range cut.
  float range_cut_share = 0.98f;
};

// How many of a frame's points describe its pieces (`segmenter.description`).
struct DescriptionOptions {
  // Larger clouds are assigned, split into pieces and described from a stratified subsample of
  // at most this many points (a 640x480 cloud: one in 8); support counts are scaled back to the
  // whole cloud, extents are within a sample spacing of the whole cloud's. The angular step
  // that sets the reach is the subsample's own. 0: every point (as with keep_labels).
  int points_max = 40000;
  // Pieces are fitted to one in s of the described points, s chosen so at most this many enter
  // the fits (errors grow as 1 / sqrt(points); far fewer points than a frame holds leave them
  // below the systematic ones). Support counts, connectivity and extents use every described
  // point.
  int fit_points_max = 80000;
  // A piece whose RMS is over this many times the noise expected along its normal leans between
  // two surfaces and takes the line most of its points lie on (dominant line fit), if that line
  // holds at least min_line_share of them.
  double leaning_rms = 3.0;
  double min_line_share = 0.5;
  int min_noise_points = 50;  // pieces with fewer points within their trim do not vote on the noise
};

struct Options {
  NoiseOptions noise;
  EmOptions em;
  ProposalOptions proposals;
  MergeOptions merge;
  SeedOptions seeds;
  AssignmentOptions assignment;
  ExtentOptions extents;
  DescriptionOptions description;
  // The depth camera, when the segmenter is told (sensor.hpp): its noise per range replaces
  // noise.range_noise, sets a floor under every plane's noise and bands that grow with depth.
  SensorOptions sensor;
  bool keep_labels = false;  // fill Result::labels (pictures, tests)
  uint32_t seed = 1;         // proposals' random choices; fixed per frame for determinism
};

}  // namespace relplane::segmenter
