// Closed planar polygon.
#pragma once

#include <Eigen/Core>

namespace scanstation {

/// vertices  #N by 2 in boundary order; the polygon is closed implicitly
///           (vertex N-1 connects back to vertex 0)
struct Polygon2 {
  Eigen::MatrixX2d vertices;

  Eigen::Index size() const { return vertices.rows(); }
};

/// Many polygon files list a ring's first vertex again at its end (SVG paths
/// closed by hand, GIS rings). The polygon is closed implicitly here, so such
/// trailing copies (equal to the first vertex bit for bit) are dropped, while
/// at least 3 vertices remain. Returns how many were dropped.
Eigen::Index drop_closing_repeat(Polygon2& polygon);

/// Twice the signed area (shoelace); positive for counter-clockwise order.
double twice_signed_area(const Polygon2& polygon);

/// Sum of edge lengths, including the closing edge.
double perimeter(const Polygon2& polygon);

/// True when no two non-adjacent edges meet and no vertex repeats, decided
/// with exact predicates (CGAL::is_simple_2). Needs at least 3 vertices.
bool is_simple(const Polygon2& polygon);

}  // namespace scanstation
