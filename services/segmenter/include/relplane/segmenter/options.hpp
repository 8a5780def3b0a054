#pragma once
// Options of the EM plane segmenter. Defaults work for depth sensors with noise up to
// sigma = 2 cm along the normal; the service fills them from the scenario's `segmenter` section.

#include <cstdint>

#include "relplane/segmenter/sensor.hpp"

namespace relplane::segmenter {

struct Options {
  // --- Noise model (E-step) ---
  // Each plane learns its own noise sigma (the weighted RMS of its support), kept in
  // [sigma_min, sigma_max]; sigma_min keeps noise-free clouds well conditioned.
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

  // --- EM on a subsample ---
  // EM runs on a subsample of cloud_size / em_fraction points, clamped to
  // [em_points_min, em_points_max] (a 640x480 cloud: 5000 points; 160x120: 2000).
  int em_points_min = 2000;
  int em_points_max = 5000;
  int em_fraction = 60;
  int em_iterations = 8;           // E/M iterations per round (fewer once converged)
  int max_rounds = 6;              // rounds of EM + add/merge/prune
  int max_planes = 24;             // mixture components at most
  float converged_angle = 1e-4f;   // radians: a plane moving less has converged
  float converged_offset = 1e-4f;  // metres

  // --- Proposals on unexplained points ---
  int proposal_trials = 40;        // local neighbourhoods tried per proposal
  int proposal_neighbours = 30;    // a trial fits the seed point's nearest unexplained points
  float proposal_radius = 0.5f;    // metres, at most this far from the seed
  float proposal_max_rms = 0.03f;  // metres, a neighbourhood flatter than this may seed a plane
  int max_proposals_per_round = 4;

  // --- Merge and prune ---
  float merge_angle_deg = 3.0f;  // near-identical planes: normals within this angle ...
  float merge_distance = 0.04f;  // ... and each centroid this close to the other plane
  // Touching pieces are one surface when their normals are within this angle (and both
  // centroids within merge_distance): lets a depth camera's few-degree bend at the image edge
  // stay part of the floor.
  float piece_merge_angle_deg = 6.0f;
  // Vertical pieces lying over each other along and up the wall, over most of the smaller one,
  // each centroid within merge_distance of the other's plane, are one surface when their normals
  // are within this angle: a depth sensor cannot see two surfaces there. At 1 cm noise EM fitted
  // a 0.3 m pilaster side 2 m ahead as two planes 9 degrees apart, each with about half its
  // points over the whole face, in 7 % of a hallway loop's frames, and the pose swung 2 cm
  // across the hallway and back while they were in view (services/mapper/NOTES.md).
  float overlap_merge_angle_deg = 20.0f;
  int min_em_points = 12;  // EM support (sum of responsibilities) below this is pruned

  // --- Assignment of all points and extent ---
  float inlier_sigmas = 3.0f;  // a point supports its nearest plane within this many sigma
  int min_points = 150;        // pieces with fewer supporting points are dropped
  float cell_size = 0.1f;      // metres, occupancy grid in the plane for connected pieces
  int cell_reach = 2;          // cells: occupied cells this close are connected, at least
  // Further where the samples land further apart (far away, grazing incidence): cells connect
  // within this many expected sample spacings (learnt from the cloud; 0: cell_reach only) ...
  float reach_spacings = 1.5f;
  float max_reach = 1.5f;  // ... but never beyond this, metres
  int max_cells = 250000;  // the grid coarsens beyond this many cells per plane
  // Pieces are fitted to one in s of the described points (see describe_points_max), s chosen so
  // at most this many enter the fits (errors grow as 1 / sqrt(points), and 75,000 points leave
  // them far below the systematic ones). Support counts, connectivity and extents use every
  // described point.
  int fit_points_max = 80000;
  // Larger clouds are assigned, split into pieces and described from a stratified subsample of
  // at most this many points (a 640x480 cloud: one in 8); support counts are scaled back to the
  // whole cloud, extents are within a sample spacing of the whole cloud's. The angular step
  // that sets the reach is the subsample's own. 0: every point (as with keep_labels).
  int describe_points_max = 40000;
  // A vertical piece's ends where its samples put them on average, not at its extreme points
  // (wall_ends.hpp): the extreme lands up to a ray spacing short far off and past the end by
  // the noise nearby. On by default with the two options below: together they took the mapper's
  // seeded runs at 1 cm noise from 43 to 58 of 72 (services/mapper/NOTES.md, "Wall ends from the segmenter").
  bool wall_end_estimate = true;
  float vertical_max_nz = 0.1f;  // |normal.z| below this is a vertical plane: rectangle extent
  // Take the sensor's noise along its rays out of each piece's fit (FitOutRayNoise in
  // merge_pieces.hpp): a plain fit of a short piece seen off to one side tilts towards its rays
  // (1.7 degrees for a 0.15 m wall piece at 1 cm): office_other_sensor's door-frame jambs, up
  // to 2.6 degrees off, turned its heading by up to 0.6 degrees (services/segmenter/README.md).
  bool ray_noise_fit = true;
  // A vertical piece whose RMS is well over the noise the frame's other walls show along its
  // normal is refitted to the one line, seen from above, that most of its points lie on
  // (DominantLineFit, dominant_line.hpp), and the frame is assigned again with its mixture plane
  // set to that line (segmenter.cpp): a grazing pilaster front whose mixture plane leaned
  // towards the side it meets and took the side's samples up to 10 cm from the corner. At 1 cm
  // noise such fronts leaned up to 7.7 degrees and the sides were seen 0.1 m short; over seeds
  // 1-72 of loop_other_sensor the mapper met its targets on 64 runs without, 72 with (services/mapper/NOTES.md).
  bool dominant_line_fit = true;

  // Drop the mixture planes that form no piece and assign the frame again without them
  // (segmenter.cpp: a noise-free frame's rows of floor and ceiling samples and a wall column at
  // one depth form a plane that cut wall pieces short).
  bool drop_pieceless_planes = true;

  // The depth camera, when the segmenter is told (sensor.hpp): its noise per range replaces
  // range_noise, sets a floor under every plane's noise and bands that grow with depth.
  SensorOptions sensor;

  bool keep_labels = false;  // fill Result::labels (pictures, tests)
  uint32_t seed = 1;         // proposals' random choices; fixed per frame for determinism
};

}  // namespace relplane::segmenter
