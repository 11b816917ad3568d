#include "smoothing/polygon_tangents.h"

#include "core/errors.h"
#include "core/unit_scale.h"

#include <string>

namespace scanstation {

Eigen::MatrixX2d polygon_tangents(const Polygon2& polygon, TangentWeighting weighting) {
  const Eigen::Index n = polygon.size();
  if (n < 3) throw InvalidInput("a closed curve needs at least 3 vertices, got " + std::to_string(n));
  const auto& V = polygon.vertices;
  // Near 1e±160 the squared lengths leave the double range (every vertex
  // looked repeated): the same tangents from the copy scaled by a power of two.
  if (const double s = unit_scale(V); beyond_squares(s)) {
    Polygon2 scaled = polygon;
    scaled.vertices *= s;
    return polygon_tangents(scaled, weighting);
  }
  Eigen::MatrixX2d T(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d in = V.row(i) - V.row((i + n - 1) % n);
    const Eigen::Vector2d out = V.row((i + 1) % n) - V.row(i);
    if (in.squaredNorm() == 0.0 || out.squaredNorm() == 0.0)
      throw InvalidInput("polygon vertex " + std::to_string(i) + " repeats its neighbour: remove duplicate vertices");
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    switch (weighting) {
      case TangentWeighting::length: sum = in + out; break;
      case TangentWeighting::uniform: sum = in.normalized() + out.normalized(); break;
      case TangentWeighting::inverse_length: sum = in / in.squaredNorm() + out / out.squaredNorm(); break;
    }
    if (sum.squaredNorm() == 0.0)
      throw InvalidInput("polygon vertex " + std::to_string(i) + ": the boundary reverses there, no tangent exists");
    T.row(i) = sum.normalized();
  }
  return T;
}

}  // namespace scanstation
