// Points a boundary through every point reaches with a spike: stray readings
// far from all others, and points among others that the boundary reaches
// with long faces all the same.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace scanstation {

/// The vertices a boundary reaches with a spike, in two kinds.
struct SpikedPoints {
  /// Far from all other points too (a stray reading, a far outlier): the
  /// faces around them are no longer those of the object, and removing
  /// outliers before reconstruction is the cure.
  std::vector<int> far;
  /// With other points near, yet reached only by long edges: the boundary
  /// missed the surface there (constriction locked around them and
  /// augmentation, §5.4, brought them on; thin walls, sparse sampling).
  std::vector<int> reached;
};

/// The vertices of a boundary whose shortest boundary edge is more than
/// `factor` times the median shortest edge of the vertices, split by their
/// distance to the nearest other point of V (also over `factor` times that
/// median: far; else reached).
/// V       #V by D vertex positions (D = 2 or 3), distinct
/// cycles  #F by k: each row's corners in order, joined cyclically, are
///         edges (triangles, k = 3; a polygon's edges, k = 2)
/// Both lists in increasing order; empty when fewer than 3 vertices lie on
/// an edge or the median edge has length 0.
SpikedPoints spiked_points(const Eigen::MatrixXd& V, const Eigen::MatrixXi& cycles, double factor = 100.0);

/// spiked_points(V, cycles, factor).far: the points far from all others.
std::vector<int> far_points(const Eigen::MatrixXd& V, const Eigen::MatrixXi& cycles, double factor = 100.0);

}  // namespace scanstation
