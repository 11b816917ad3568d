// The cubic three-split scheme (thesis §9.6, Clough–Tocher-like): a
// tangent-plane continuous surface of cubic Bézier triangles through the
// vertices of a closed triangle mesh with prescribed normals.
#pragma once

#include "smoothing/bezier_surface.h"
#include "smoothing/mesh_edges.h"

#include <Eigen/Core>
#include <limits>

namespace scanstation {

/// least_squares_ratio  Equations (9.3a) and (9.3d) fix the coefficients
///   at each end of a macro edge only up to a factor, so λ = e1/e0 is free;
///   the thesis sets e0 = e1 = 1 (false). When true, λ minimises the
///   displacement of L1 and R1 from their subdivided positions, in the spirit
///   of the six-split's Step 5 (our addition; still exactly Equation 9.3).
/// tension  the Step-2 constant (1/3 in the thesis), see macro_patches.
/// max_move  where Equation (9.4) is nearly dependent its solution can move
///   L1 or R1 farther than this many macro edge lengths (a bulge); the edge is
///   then joined by a bounded damped least-squares step instead (not G¹
///   there, counted in dependent_edges). ∞: always exact, as the thesis.
struct ThreeSplitOptions {
  bool least_squares_ratio = false;
  double tension = 1.0 / 3.0;
  double max_move = std::numeric_limits<double>::infinity();
};

/// V #V by 3, F #F by 3 (closed, oriented), N #V by 3 unit normals, edges =
/// mesh_edges(F). Steps 1–3 (macro_patches), Step 4: each macro triangle is
/// split at P(1/3,1/3,1/3) into micro triangles (V_k, V_k+1, C), patch 3f+k;
/// Step 5: L1 and R1 of every macro edge from Equation (9.4), with e0 = e1 = 1
/// and f_i, g_i from Equations (9.3a) and (9.3d) (when (9.4) is singular, the
/// solution closest to the subdivided L1, R1, counted in dependent_edges); Step 6: Y_i = (W_i + X_i +
/// X_i−1)/3, Z = (Y_1 + Y_2 + Y_3)/3 [Farin, 83].
BezierSurface three_split(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N,
                          const MeshEdges& edges, const ThreeSplitOptions& options = {});

/// The scheme's steps one macro triangle or edge at a time, for schemes that
/// combine it with other splits (the adaptive two-split of §9.7).
/// Step 4: micro[k] = the macro patch on (V_k, V_k+1, centroid), k = 0..2.
void split_in_three(const CubicTriangle& macro, CubicTriangle* micro);
/// Step 5 on the macro edge between micro triangles P (this side, edge b300 →
/// b030) and Q (the other side): sets L1 = P's b111 and R1 = Q's b111 by
/// Equation (9.4); false when (9.4) was dependent (closest solution taken)
/// or its solution moved a point more than max_move edge lengths (the bounded
/// damped step taken, see ThreeSplitOptions).
bool join_three_split_edge(CubicTriangle& P, CubicTriangle& Q, bool least_squares_ratio,
                           double max_move = std::numeric_limits<double>::infinity());
/// Step 6 inside one macro triangle: Y_i and Z from W_i and X_i [Farin, 83].
void join_three_split_interior(CubicTriangle* micro);

}  // namespace scanstation
