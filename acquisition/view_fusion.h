// Fusion of per-view point clouds that are already in the object frame
// (stereo views, laser sweeps): points of all views falling into the same
// small cube merge into one, weighted by confidence; cubes seen by too few
// views and isolated points are dropped.
#pragma once

#include "acquisition/laser_triangulation.h"

#include <vector>

namespace scanstation::acquisition {

/// voxel           side of the cubes in which points merge (station units), > 0
/// minimum_views   a cube needs points from at least this many views: a
///                 surface seen from neighbouring turntable angles repeats,
///                 a mismatch rarely does
/// outlier_radius  after merging, points with fewer than `min_neighbours`
///                 others within this radius go (remove_isolated_points);
///                 0 keeps them all
struct FusionOptions {
  double voxel = 0.5;
  int minimum_views = 1;
  double outlier_radius = 0;
  int min_neighbours = 4;
};

/// views  per-view points in the object frame, each with colours and one
///        confidence per point (or none: confidence 1)
/// Returns one point per kept cube, in the order the cubes were first hit:
/// the confidence-weighted mean position and colour, and the confidence
/// 1 − Π(1 − cᵢ) of its points (agreeing points make a point surer).
/// Deterministic. Throws InvalidInput for a voxel ≤ 0, a view whose colours
/// or confidences do not match its points, or points more than 2²⁰ cubes
/// from the origin.
LaserScanPoints fuse_views(const std::vector<LaserScanPoints>& views, const FusionOptions& options = {});

}  // namespace scanstation::acquisition
