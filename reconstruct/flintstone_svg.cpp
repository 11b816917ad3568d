#include "reconstruct/flintstone_svg.h"

#include "core/bounding_box.h"
#include "core/svg_canvas.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scanstation {

Eigen::MatrixX2d flintstone_outline(const Flintstone<2>& stone, int samples) {
  std::vector<Eigen::Vector2d> points;
  const std::array<const SignedBall<2>*, 2> balls = {&stone.first, &stone.second};
  for (int b = 0; b < 2; ++b) {
    const SignedBall<2>& ball = *balls[static_cast<std::size_t>(b)];
    const SignedBall<2>& other = *balls[static_cast<std::size_t>(1 - b)];
    for (int k = 0; k < samples; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / samples;
      const Eigen::Vector2d x = ball.center + ball.radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      // Intersection: the arcs inside the other disc; union: outside it.
      const bool inner = (x - other.center).norm() <= other.radius * (1.0 + 1e-9);
      if (stone.degenerate || inner != stone.is_union) points.push_back(x);
    }
  }
  if (points.empty()) return Eigen::MatrixX2d(0, 2);
  // Both outlines are star-shaped around their mean (a lens is convex).
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  std::sort(points.begin(), points.end(), [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return std::atan2(a.y() - mean.y(), a.x() - mean.x()) < std::atan2(b.y() - mean.y(), b.x() - mean.x());
  });
  Eigen::MatrixX2d outline(static_cast<Eigen::Index>(points.size()), 2);
  for (std::size_t k = 0; k < points.size(); ++k) outline.row(static_cast<Eigen::Index>(k)) = points[k].transpose();
  return outline;
}

std::string flintstone_svg(const FlintstoneTree2& tree, const PolygonApproximation& approximation) {
  Eigen::AlignedBox2d bounds = bounding_box(tree.vertices);
  for (const Chain2& piece : approximation.pieces)
    if (piece.node >= 0) {
      const Eigen::MatrixX2d outline = flintstone_outline(tree.nodes[static_cast<std::size_t>(piece.node)].stone);
      if (outline.rows() > 0) bounds.extend(bounding_box(outline));
    }
  SvgCanvas canvas(bounds);
  for (const Chain2& piece : approximation.pieces)
    if (piece.node >= 0)
      canvas.polygon(flintstone_outline(tree.nodes[static_cast<std::size_t>(piece.node)].stone),
                     SvgStyle{"#4a78c2", "#dbe6f7", 0.8, 0.0, ""});
  canvas.polygon(tree.vertices, SvgStyle{"#8a8a8a", "none", 1.0, 0.0, ""});
  Eigen::MatrixX2d approximated(static_cast<Eigen::Index>(approximation.vertices.size()), 2);
  for (std::size_t k = 0; k < approximation.vertices.size(); ++k)
    approximated.row(static_cast<Eigen::Index>(k)) = tree.vertices.row(approximation.vertices[k]);
  canvas.polygon(approximated, SvgStyle{"black", "none", 1.8, 0.0, ""});
  canvas.points(approximated, SvgStyle{"none", "#c0392b", 0.0, 2.5, ""});
  char caption[160];
  std::snprintf(caption, sizeof caption, "level %d, %zu of %d vertices, e1 %.3g, e2 %.3g, e5 %.3g", approximation.level,
                approximation.vertices.size(), tree.size(), approximation.errors.e1, approximation.errors.e2,
                approximation.errors.e5);
  canvas.caption(caption);
  return canvas.str();
}

}  // namespace scanstation
