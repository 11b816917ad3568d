// Closed G¹ piecewise cubic Bézier curve through the vertices of a polygon
// (thesis §9.2, Figure 9.1).
#pragma once

#include "core/polygon.h"

#include <Eigen/Core>
#include <vector>

namespace scanstation {

/// controls  #3N by 2: segment i has control points rows 3i, 3i+1, 3i+2 and
///           3(i+1) mod 3N, so row 3i is vertex v_i
/// tangents  #N by 2 unit tangents used (after repairs)
/// repaired_vertices  vertices whose tangent was changed because the
///           projections p3* and q0* fell on the same side of v_i (a cusp)
/// unrepaired_vertices  cusps no tangent can remove (the polygon reverses)
struct G1Curve {
  Eigen::MatrixX2d controls;
  Eigen::MatrixX2d tangents;
  std::vector<Eigen::Index> repaired_vertices;
  std::vector<Eigen::Index> unrepaired_vertices;

  Eigen::Index segment_count() const { return controls.rows() / 3; }
  /// Control point j (0..3) of segment i.
  Eigen::Vector2d control(Eigen::Index i, int j) const { return controls.row((3 * i + j) % controls.rows()); }
};

/// polygon  #N ≥ 3 vertices; tangents  #N by 2 unit tangent estimates (see
/// polygon_tangents). Each segment v(i−1)→v(i) gets p1 = p0 + (p3* − p0)/3
/// and p2 = p3 + (p0* − p3)/3, p* the orthogonal projection onto the other
/// end's tangent line (§9.2). Where p3* and q0* lie on the same side of v_i
/// the curve would cusp; the tangent there is replaced by the uniformly
/// weighted one (sum of the unit edge vectors), which always separates them
/// unless the polygon reverses exactly at v_i.
G1Curve g1_curve(const Polygon2& polygon, const Eigen::MatrixX2d& tangents);

/// Point of segment i at parameter t in [0, 1] (de Casteljau).
Eigen::Vector2d curve_point(const G1Curve& curve, Eigen::Index segment, double t);

/// Largest angle (radians) between the end tangent of segment i−1 and the
/// start tangent of segment i over all vertices: 0 for a G¹ curve (Definition 8.4).
double max_tangent_angle(const G1Curve& curve);

}  // namespace scanstation
