// Vertex normals that keep the cross-edge control points of every macro edge
// end apart (thesis §9.6, §9.8: "the normal vector at a vertex should be
// altered" where the tangent plane orientation is not properly defined).
#pragma once

#include "smoothing/mesh_edges.h"

#include <Eigen/Core>
#include <vector>

namespace scanstation {

/// Which points stand next to a macro edge's end V, on either side of the
/// edge V → A between the triangles (V, A, B) and (V, C, A); p_X is X − V
/// projected onto the tangent plane at V (Step 2).
enum class CrossEdgePoints {
  step_two,   ///< three-split: the Step-2 points, along p_B and p_C
  step_zero,  ///< six-split: the Step-0 points N, along p_A + p_B and p_A + p_C
};

/// Equation (9.3a) writes the edge direction p_A as a combination of the two
/// cross-edge directions; when those two line up (by symmetry, as at the
/// corners of a cube split into triangles) it has no solution and the edge
/// cannot be G¹ at V. At every vertex where some end's two directions make an
/// angle whose sine is below min_sine, the normal is replaced by the
/// candidate (the normal tilted towards or away from each incident face
/// normal by 1°–16°, and the uniformly weighted normal) that keeps them
/// farthest from parallel, among those keeping min_f n·n_f at least
/// min(0.05, its present value) (the sign condition stays as it was).
///
/// V #V by 3, F #F by 3 closed and oriented, N #V by 3 unit normals (updated
/// in place), edges mesh_edges(F).
/// returns  the vertices whose normal was changed, ascending.
std::vector<int> separate_cross_edge_directions(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                                const MeshEdges& edges, CrossEdgePoints points, Eigen::MatrixX3d& N,
                                                double min_sine = 1e-6);

}  // namespace scanstation
