// The adaptive splitting scheme (thesis §9.7): thin macro triangles and their
// neighbour across the longest edge are split in two at that edge's midpoint
// (the two-split), every other macro triangle in three (the three-split of
// §9.6). A two-split keeps the small angles of a thin triangle whole instead
// of dividing them at the centroid.
#pragma once

#include "smoothing/bezier_surface.h"
#include "smoothing/mesh_edges.h"
#include "smoothing/three_split.h"

#include <Eigen/Core>
#include <vector>

namespace scanstation {

/// A two-split pair: macro triangle `face` and its neighbour across its local
/// edge `edge` (corner edge → edge+1), both split at that edge's midpoint.
struct TwoSplitPair {
  int face;
  int edge;
};

/// The pairs chosen adaptively: every macro triangle whose smallest angle is
/// below min_angle_degrees, thinnest first, is paired with its neighbour across
/// its longest edge, provided neither is paired or an outer neighbour of a
/// pair yet, and its four outer neighbours are in no pair (§9.7: "it has been
/// essential that the two two-split triangles have four three-split triangles
/// as neighbors"). A three-split triangle may border two or three pairs (the
/// thesis: "it should be possible to achieve tangent plane continuity when two
/// or three sides of a triangle are split"). V #V by 3, F #F by 3, edges =
/// mesh_edges(F).
std::vector<TwoSplitPair> two_split_pairs(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                          const MeshEdges& edges, double min_angle_degrees);

/// V, F, N, edges as three_split; pairs from two_split_pairs (candidates).
/// Patches: 2 per two-split macro triangle, 3 per other one, in face order;
/// for a pair (P = (A, B, C) split on A → B, Q = (B, A, D)) they are
/// (A, Z, C), (Z, B, C) and (B, Z, D), (Z, A, D), Z = P(½, ½, 0); the
/// three-split ones as in three_split.
///
/// Steps 1–3 (macro_patches). The thesis' constant coefficients on all four
/// inner edges (9.6) force Y_i = Z (a singular point), and its outer edges
/// need the ratio condition of (9.7) at both ends, which "an algorithm given
/// by [Farin, 83]" arranges by moving the points next to the vertices. So:
///  - outer edges (a two-split against a three-split micro triangle): E, F, G
///    constant (Equation 9.7), (1, f, g) fitted to the subdivided points; the
///    outer edges' Step-2 points and the points next to A, B, C, D on the
///    inner edges move least (in the tangent planes) to meet the ratio
///    condition at all eight ends;
///  - Step 4 of §9.7: subdivision at Z;
///  - Step 5, the nine unknowns X_i, Y_i, Z of Figure 9.6: E, F, G constant
///    on C–Z (Equations 9.6a, b), linear on A–Z, B–Z, D–Z (Equation 9.3) with
///    the coefficients at Z implied by the star at Z ((9.6b) on C–Z and one
///    relation fitted to the subdivided points);
///  - R1 of each outer edge from (9.7b) − (9.7a);
///  - the three-split triangles: Steps 5 and 6 of §9.6 on the other edges.
/// Pairs next to each other — a three-split triangle bordering two or three
/// pairs — are coupled through its Step-2 points (the O of one pair's ratio
/// condition is a K of the other's) and their ratio conditions are solved
/// together; each outer edge is still joined by (9.7b) − (9.7a) on its own
/// micro triangle of the neighbour.
/// A candidate whose inner edges would violate the G¹ orientation (f, g of
/// opposite signs at an end) is left to the three-split. dependent_edges
/// counts macro edges and pairs whose equations were dependent.
/// counts (optional) receives the pairs built and how many of them are next
/// to another pair.
struct TwoSplitCounts {
  std::size_t pairs = 0, adjacent_pairs = 0;
};
BezierSurface two_split(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N,
                        const MeshEdges& edges, const std::vector<TwoSplitPair>& pairs,
                        const ThreeSplitOptions& options = {}, TwoSplitCounts* counts = nullptr);

}  // namespace scanstation
