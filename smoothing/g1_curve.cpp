#include "smoothing/g1_curve.h"

#include "core/errors.h"
#include "core/unit_scale.h"

#include <algorithm>
#include <cmath>

namespace scanstation {

namespace {

// p3* and q0* on opposite sides of v_i along T_i (§9.2): the incoming
// neighbour behind, the outgoing one ahead.
bool separates(const Eigen::Vector2d& previous, const Eigen::Vector2d& vertex, const Eigen::Vector2d& next,
               const Eigen::Vector2d& tangent) {
  return tangent.dot(previous - vertex) < 0.0 && tangent.dot(next - vertex) > 0.0;
}

}  // namespace

G1Curve g1_curve(const Polygon2& polygon, const Eigen::MatrixX2d& tangents) {
  const Eigen::Index n = polygon.size();
  if (n < 3) throw InvalidInput("a closed curve needs at least 3 vertices");
  if (tangents.rows() != n) throw InvalidInput("expected one tangent per polygon vertex");
  const auto& V = polygon.vertices;
  // As polygon_tangents: from the copy scaled by a power of two where squared
  // lengths would leave the double range, the control points scaled back.
  if (const double s = unit_scale(V); beyond_squares(s)) {
    Polygon2 scaled = polygon;
    scaled.vertices *= s;
    G1Curve curve = g1_curve(scaled, tangents);
    curve.controls /= s;
    return curve;
  }
  G1Curve curve;
  curve.tangents = tangents;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d previous = V.row((i + n - 1) % n), vertex = V.row(i), next = V.row((i + 1) % n);
    if (separates(previous, vertex, next, tangents.row(i))) continue;
    const Eigen::Vector2d uniform = (vertex - previous).normalized() + (next - vertex).normalized();
    if (uniform.squaredNorm() > 0.0 && separates(previous, vertex, next, uniform.normalized())) {
      curve.tangents.row(i) = uniform.normalized();
      curve.repaired_vertices.push_back(i);
    } else {
      curve.unrepaired_vertices.push_back(i);
    }
  }
  curve.controls.resize(3 * n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d p0 = V.row(i), p3 = V.row((i + 1) % n);
    const Eigen::Vector2d t0 = curve.tangents.row(i), t3 = curve.tangents.row((i + 1) % n);
    const Eigen::Vector2d p3_star = p0 + t0 * t0.dot(p3 - p0);  // projection onto Tline at p0
    const Eigen::Vector2d p0_star = p3 + t3 * t3.dot(p0 - p3);  // projection onto Tline at p3
    curve.controls.row(3 * i) = p0;
    curve.controls.row(3 * i + 1) = p0 + (p3_star - p0) / 3.0;
    curve.controls.row(3 * i + 2) = p3 + (p0_star - p3) / 3.0;
  }
  return curve;
}

Eigen::Vector2d curve_point(const G1Curve& curve, Eigen::Index segment, double t) {
  Eigen::Vector2d b[4];
  for (int j = 0; j < 4; ++j) b[j] = curve.control(segment, j);
  for (int level = 3; level > 0; --level)
    for (int j = 0; j < level; ++j) b[j] = (1.0 - t) * b[j] + t * b[j + 1];
  return b[0];
}

double max_tangent_angle(const G1Curve& curve) {
  const Eigen::Index n = curve.segment_count();
  double worst = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index before = (i + n - 1) % n;
    // Near unit length: at any scale the products stay in range.
    const Eigen::Vector2d end = near_unit<2>(curve.control(before, 3) - curve.control(before, 2));
    const Eigen::Vector2d start = near_unit<2>(curve.control(i, 1) - curve.control(i, 0));
    const double angle = std::atan2(std::abs(end.x() * start.y() - end.y() * start.x()), end.dot(start));
    worst = std::max(worst, angle);
  }
  return worst;
}

}  // namespace scanstation
