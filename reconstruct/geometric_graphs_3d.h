// The edge graphs of Veltkamp's chapter 2 for points in space: closest pairs,
// nearest neighbours, the Euclidean minimum spanning tree, the relative
// neighbourhood and the Gabriel graph, from one Delaunay tetrahedralization,
// so that CP ⊆ NNG ⊆ EMST ⊆ RNG ⊆ GG ⊆ DT as in the plane
// (reconstruct/geometric_graphs.h, whose conventions these follow).
//
// Every function takes
//   V  #V by 3 positions
// and returns
//   E  #E by 2 edges, i < j, rows sorted lexicographically.
// Duplicate positions are merged: the first occurrence takes part, later
// copies are isolated. Every decision is an exact predicate (CGAL Epick);
// degenerate input is normal: a Gabriel chord that CGAL's tetrahedralization
// leaves out (co-spherical points, co-circular points in a plane, as on a
// lattice) is found from the cluster of cells sharing its empty sphere.
// Non-finite input throws scanstation::InvalidInput, and so do more than 300
// points in one plane (give those as 2D points).
#pragma once

#include <Eigen/Core>

namespace scanstation {

/// Definition 2.9: no vertex strictly inside the sphere with diameter ij.
Eigen::MatrixX2i gabriel_graph(const Eigen::MatrixX3d& V);

/// Definition 2.8: no vertex k with max(|ik|, |jk|) < |ij|; Gabriel edges
/// screened by a k-d tree query of the ball of radius |ij| around i.
Eigen::MatrixX2i relative_neighborhood_graph(const Eigen::MatrixX3d& V);

/// Definition 2.5: Kruskal on the Gabriel edges (an EMST is among them);
/// lengths compared exactly, ties broken by (i, j).
Eigen::MatrixX2i euclidean_minimum_spanning_tree(const Eigen::MatrixX3d& V);

/// Definition 2.4: each vertex joined to one nearest vertex, the smallest
/// index among equally near ones (consistent with the EMST order).
Eigen::MatrixX2i nearest_neighbor_graph(const Eigen::MatrixX3d& V);

/// Definition 2.3: every pair at the minimum distance.
Eigen::MatrixX2i closest_pairs(const Eigen::MatrixX3d& V);

}  // namespace scanstation
