// The cubic six-split scheme (thesis §9.8): every macro triangle is split at
// its centroid O and edge midpoints Z into six cubic micro triangles; the
// control points near each Z are set by constrained least squares (Step 5),
// the rest so that the micro triangles of one macro triangle join C¹.
#pragma once

#include "smoothing/bezier_surface.h"
#include "smoothing/mesh_edges.h"

#include <Eigen/Core>
#include <limits>

namespace scanstation {

/// V #V by 3, F #F by 3 (closed, oriented), N #V by 3 unit normals, edges =
/// mesh_edges(F). Patch 6f+j is micro triangle j of face f: for corner c,
/// j = 2c is (V_c, Z_c, O) and j = 2c+1 is (Z_c, V_c+1, O).
///
/// Steps 1–4 as §9.8 (macro patches, subdivision, N by Equation 9.14 with
/// N − V = ⅔((K0 − V) + (K1 − V)), i.e. the thesis' b = −2/3 with its signs:
/// the only value for which the conditions (9.10b) at Z are not degenerate,
/// see docs/design.md).
/// Step 5, per macro edge: Z, its four neighbours Y and the four centres X
/// around Z move least (least squares) subject to
///   Z = (Y_a + Y_b)/2 = (Y_f + Y_g)/2   (the star at Z: a common tangent plane),
///   Y_f = (X_a + X_b)/2, Y_g likewise  (Equation 9.10a on the edges to O, O'),
///   Equation (9.3b, c) on both macro half edges, with linear E, F, G fixed at
///   the vertex end by the tangent plane (Equation 9.9a) and at Z to (1, −½, −½).
/// Solved once per macro edge in closed form (the two (9.3b) rows give Y_a,
/// Y_b; the rest is a 3×4 system in the centres with a one-dimensional null
/// space, see docs/design.md), the pseudo-inverse where the constraints are
/// dependent (counted in dependent_edges). Where the exact solution folds
/// the surface (the two sides' normals turned by π somewhere along the edge,
/// which thin macro triangles at a vertex can demand), or moves a point
/// farther than max_move macro edge lengths (a bulge), the edge is joined by
/// a damped least-squares step of bounded move instead: not G¹ there, and
/// counted in dependent_edges too; so is an edge whose subdivided star at Z
/// folds (made C¹ instead, φ = ψ = −½, which avoids the fold but is no G¹
/// join). With a finite max_move, an exact solution whose patches turn over
/// between a vertex and Z (both sides together, the normal turned by π/2 or
/// more from the vertex's) is joined by the damped step as well where one
/// mends it. max_move = ∞ keeps every non-folding exact solution, as the
/// thesis.
/// Steps 6–7: Q at the vertex edges from Equation (9.13a), Q at the midpoint
/// edges the mean of their neighbours (9.12a), O = (Q0 + Q2 + Q4)/3 — the
/// domain ratios of the split, so the interior joins C¹.
/// tension  the Step-2 constant of the macro patches (1/3 in the thesis).
/// One pass over the macro triangles, each written once, complete; memory
/// per macro triangle: 1440 bytes of patches and 24 of `macro` kept, 12 more
/// while building, and 144 bytes per macro edge between the triangles done
/// and those to come (a few thousand edges when F is in a local order).
BezierSurface six_split(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N,
                        const MeshEdges& edges, double tension = 1.0 / 3.0,
                        double max_move = std::numeric_limits<double>::infinity());

/// The same into `surface`, replacing what it held and reusing its memory (no
/// new pages when it held at least as many patches), for repeated smoothing
/// of one mesh or of meshes of similar size.
void six_split(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N, const MeshEdges& edges,
               double tension, BezierSurface& surface, double max_move = std::numeric_limits<double>::infinity());

}  // namespace scanstation
