// Points far from all others on a boundary through every point.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace scanstation {

/// The vertices of a boundary that lie far from all the others: those whose
/// shortest edge is more than `factor` times the median shortest edge of
/// the vertices. A boundary through every point reaches such a point (a
/// stray reading, a far outlier) with long faces, a spike, and the faces
/// around it are no longer those of the object.
/// V       #V by D vertex positions (D = 2 or 3)
/// cycles  #F by k: each row's corners in order, joined cyclically, are
///         edges (triangles, k = 3; a polygon's edges, k = 2)
/// Returns the far vertices in increasing order; empty when fewer than 3
/// vertices lie on an edge or the median edge has length 0.
std::vector<int> far_points(const Eigen::MatrixXd& V, const Eigen::MatrixXi& cycles, double factor = 100.0);

}  // namespace scanstation
