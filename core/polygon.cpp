#include "core/polygon.h"

#include "core/unit_scale.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

#include <vector>

namespace scanstation {

// Relative to the bounding box's centre, as enclosed_volume (far from the
// origin the shoelace terms cancel and their rounding swamps the area).
// Both scaled by a power of two where the squares of lengths leave the
// double range (as surface_area).
Polygon2 scaled(const Polygon2& polygon, double s) {
  Polygon2 out = polygon;
  out.vertices *= s;
  return out;
}

double twice_signed_area(const Polygon2& polygon) {
  const Eigen::Index n = polygon.size();
  if (n == 0) return 0.0;
  if (const double s = unit_scale(polygon.vertices); beyond_squares(s))
    return std::ldexp(twice_signed_area(scaled(polygon, s)), -2 * std::ilogb(s));
  const Eigen::RowVector2d o = 0.5 * (polygon.vertices.colwise().minCoeff() + polygon.vertices.colwise().maxCoeff());
  double sum = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::RowVector2d p = polygon.vertices.row(i) - o;
    const Eigen::RowVector2d q = polygon.vertices.row((i + 1) % n) - o;
    sum += p.x() * q.y() - q.x() * p.y();
  }
  return sum;
}

double perimeter(const Polygon2& polygon) {
  const Eigen::Index n = polygon.size();
  if (n == 0) return 0.0;
  if (const double s = unit_scale(polygon.vertices); beyond_squares(s))
    return std::ldexp(perimeter(scaled(polygon, s)), -std::ilogb(s));
  double sum = 0.0;
  for (Eigen::Index i = 0; i < n; ++i)
    sum += (polygon.vertices.row((i + 1) % n) - polygon.vertices.row(i)).norm();
  return sum;
}

Eigen::Index drop_closing_repeat(Polygon2& polygon) {
  Eigen::Index n = polygon.size();
  while (n > 3 && polygon.vertices.row(n - 1) == polygon.vertices.row(0)) --n;
  const Eigen::Index dropped = polygon.size() - n;
  if (dropped > 0) polygon.vertices.conservativeResize(n, 2);
  return dropped;
}

bool is_simple(const Polygon2& polygon) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  if (polygon.size() < 3) return false;
  std::vector<Kernel::Point_2> points;
  points.reserve(static_cast<std::size_t>(polygon.size()));
  for (Eigen::Index i = 0; i < polygon.size(); ++i)
    points.emplace_back(polygon.vertices(i, 0), polygon.vertices(i, 1));
  return CGAL::is_simple_2(points.begin(), points.end(), Kernel());
}

}  // namespace scanstation
