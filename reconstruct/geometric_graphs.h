// The geometric graphs of Veltkamp's chapter 2, built from one Delaunay
// triangulation where the theory allows (all are subgraphs of DT except the
// β-skeletons with b < 0), so that CP ⊆ NNG ⊆ EMST ⊆ RNG ⊆ GG ⊆ DT. The
// edge graphs CP, NNG, EMST, RNG and GG also in space (3D overloads, in
// geometric_graphs_3d.cpp): from CGAL's tetrahedralization, plus the chords
// it chose between where points are co-spherical (both diagonals of a
// lattice square are Gabriel, one is a tetrahedralization edge); RNG lunes
// by a k-d tree range search. Input with no tetrahedralization (all points
// in one plane, or fewer than four) takes every pair as a candidate up to
// 300 points and throws InvalidInput beyond (give those as 2D points).
//
// Every function takes
//   V  #V by 2 (or 3) positions
// and returns
//   E  #E by 2 edges, i < j, rows sorted lexicographically.
// Duplicate positions are merged: the first occurrence takes part, later
// copies are isolated. Decisions use exact predicates (CGAL Epick) unless a
// function says otherwise. Non-finite input throws scanstation::InvalidInput.
#pragma once

#include <Eigen/Core>

namespace scanstation {

/// Definition 2.11. Edges of one Delaunay triangulation (CGAL's choice when
/// more than 3 points are co-circular; γ([-1,1],[0,1]) has all chords then).
Eigen::MatrixX2i delaunay_edges(const Eigen::MatrixX2d& V);

/// Definition 2.10: edges with no vertex in one open half-plane nor on the
/// edge; collinear hull points give consecutive edges. Collinear input gives
/// the chain of consecutive points.
Eigen::MatrixX2i convex_hull_edges(const Eigen::MatrixX2d& V);

/// Definition 2.9: no vertex strictly inside the circle with diameter ij.
/// Includes crossing diameters of an empty circle in degenerate input.
Eigen::MatrixX2i gabriel_graph(const Eigen::MatrixX2d& V);
Eigen::MatrixX2i gabriel_graph(const Eigen::MatrixX3d& V);

/// Definition 2.8: no vertex k with max(|ik|, |jk|) < |ij| (exact distance
/// comparisons). Gabriel edges screened by a k-d tree query of the disc
/// (3D: ball) of radius |ij| around i, then the exact test on what it finds.
Eigen::MatrixX2i relative_neighborhood_graph(const Eigen::MatrixX2d& V);
Eigen::MatrixX2i relative_neighborhood_graph(const Eigen::MatrixX3d& V);

/// Definition 2.5: Kruskal on the Delaunay edges (3D: the Gabriel edges);
/// lengths compared exactly, ties broken by (i, j) so the tree is
/// deterministic. A forest never occurs (the Delaunay graph is connected).
Eigen::MatrixX2i euclidean_minimum_spanning_tree(const Eigen::MatrixX2d& V);
Eigen::MatrixX2i euclidean_minimum_spanning_tree(const Eigen::MatrixX3d& V);

/// Definition 2.4: each vertex joined to one nearest vertex, the one with the
/// smallest index among equally near ones (consistent with the EMST order, so
/// NNG ⊆ EMST always holds).
Eigen::MatrixX2i nearest_neighbor_graph(const Eigen::MatrixX2d& V);
Eigen::MatrixX2i nearest_neighbor_graph(const Eigen::MatrixX3d& V);

/// Definition 2.3: every pair at the minimum distance.
Eigen::MatrixX2i closest_pairs(const Eigen::MatrixX2d& V);
Eigen::MatrixX2i closest_pairs(const Eigen::MatrixX3d& V);

/// Definitions 2.12–2.14, the α(a)-shape. a < 0: edges ij with an empty open
/// disc of radius 1/|a| touching i and j (the closest-point α-shape, a
/// subgraph of DT); a = 0: the convex hull; a > 0: edges ij on a disc of
/// radius 1/a that holds every point (the furthest-point α-shape, on hull
/// vertices only; O(H²) for H hull vertices). Radius tests are double
/// constructions (for a < 0 against the pencil bounds of gamma_pencil_bounds).
/// Note: the thesis text says a ≥ 0 gives the closest-point subgraph; with
/// Definition 2.12 it is a ≤ 0 (empty discs).
Eigen::MatrixX2i alpha_shape_edges(const Eigen::MatrixX2d& V, double a);

enum class BetaNeighborhood { lune, circle };

/// Definitions 2.15 (circle, = γ(b,b)) and 2.16 (lune), b ∈ [-1,1]. For b ≤ 0
/// both are the lens N_βc(b). Lune with b > 0: Gabriel edges whose lune (two
/// discs of radius |ij|/(2(1-b)) centred on the line ij; b = 1 the open
/// infinite strip) is empty, membership tested in doubles except b = 1/2
/// (relative neighbourhood, exact) and b = 0 (Gabriel, exact).
Eigen::MatrixX2i beta_skeleton(const Eigen::MatrixX2d& V, double b, BetaNeighborhood kind);

}  // namespace scanstation
