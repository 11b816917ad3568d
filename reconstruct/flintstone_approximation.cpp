#include "reconstruct/flintstone_approximation.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>

namespace scanstation {

namespace {

/// Errors e1 and e2 of replacing chain p … s by the edge v_p v_s.
void chain_errors(const FlintstoneTree2& tree, const Chain2& chain, ApproximationErrors& errors) {
  const Eigen::Vector2d a = tree.point(chain.p), b = tree.point(chain.s), ab = b - a;
  const double length2 = ab.squaredNorm();
  for (int k = chain.p + 1; k < chain.s; ++k) {
    const Eigen::Vector2d x = tree.point(k) - a;
    const double t = length2 > 0.0 ? std::clamp(x.dot(ab) / length2, 0.0, 1.0) : 0.0;
    errors.e1 = std::max(errors.e1, (x - t * ab).norm());
    const double line = length2 > 0.0 ? std::abs(ab.x() * x.y() - ab.y() * x.x()) / std::sqrt(length2) : x.norm();
    errors.e2 = std::max(errors.e2, line);
  }
}

/// In-order walk that refines a chain's node when `refine` says so.
PolygonApproximation approximate(const FlintstoneTree2& tree, const std::function<bool(const FlintstoneNode2&)>& refine) {
  PolygonApproximation result;
  std::vector<Chain2> stack;
  const auto tops = tree.top_chains();
  stack.push_back(tops[1]);
  stack.push_back(tops[0]);
  while (!stack.empty()) {
    const Chain2 chain = stack.back();
    stack.pop_back();
    if (chain.node >= 0) {
      const FlintstoneNode2& node = tree.nodes[static_cast<std::size_t>(chain.node)];
      if (refine(node)) {
        result.level = std::max(result.level, node.depth);
        const auto children = tree.children(node);
        stack.push_back(children[1]);
        stack.push_back(children[0]);
        continue;
      }
      result.errors.e5 = std::max(result.errors.e5, node.stone.width());
    }
    result.vertices.push_back(tree.vertex(chain.p));
    result.pieces.push_back(chain);
    chain_errors(tree, chain, result.errors);
  }
  return result;
}

/// Distance from x to triangle a b c (closest point by regions, Ericson §5.1.5).
double point_triangle_distance(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ax = x - a;
  const double d1 = ab.dot(ax), d2 = ac.dot(ax);
  if (d1 <= 0 && d2 <= 0) return ax.norm();
  const Eigen::Vector3d bx = x - b;
  const double d3 = ab.dot(bx), d4 = ac.dot(bx);
  if (d3 >= 0 && d4 <= d3) return bx.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (x - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cx = x - c;
  const double d5 = ab.dot(cx), d6 = ac.dot(cx);
  if (d6 >= 0 && d5 <= d6) return cx.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (x - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (x - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denominator = 1.0 / (va + vb + vc);
  return (x - (a + ab * vb * denominator + ac * vc * denominator)).norm();
}

/// Errors e1 and e2 of replacing the node's faces by its corner triangle.
void node_errors(const FlintstoneTree3& tree, const FlintstoneNode3& node, ApproximationErrors& errors) {
  const auto point = [&](int v) { return Eigen::Vector3d(tree.vertices.row(v).transpose()); };
  const Eigen::Vector3d a = point(node.corners[0]), b = point(node.corners[1]), c = point(node.corners[2]);
  const Eigen::Vector3d normal = (b - a).cross(c - a);
  const double area2 = normal.norm();
  for (int k = 0; k < node.face_count; ++k)
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d x = point(tree.faces(tree.face_order[static_cast<std::size_t>(node.first_face + k)], j));
      errors.e1 = std::max(errors.e1, point_triangle_distance(x, a, b, c));
      errors.e2 = std::max(errors.e2, area2 > 0.0 ? std::abs(normal.dot(x - a)) / area2 : (x - a).norm());
    }
}

MeshApproximation approximate(const FlintstoneTree3& tree, const std::function<bool(const FlintstoneNode3&)>& refine) {
  MeshApproximation result;
  std::vector<Eigen::RowVector3i> faces;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    const FlintstoneNode3& node = tree.nodes[static_cast<std::size_t>(id)];
    if (!node.leaf() && (id == 0 || refine(node))) {
      result.level = std::max(result.level, node.depth);
      for (int c = node.child_count - 1; c >= 0; --c) stack.push_back(node.first_child + c);
      continue;
    }
    const auto [p, s, t] = node.corners;
    if (!node.leaf()) result.errors.e5 = std::max(result.errors.e5, node.stone.width());
    node_errors(tree, node, result.errors);
    if (p == s || s == t || t == p) continue;  // a void triangle
    faces.emplace_back(p, s, t);
    result.pieces.push_back(id);
  }
  result.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t k = 0; k < faces.size(); ++k) result.faces.row(static_cast<Eigen::Index>(k)) = faces[k];
  return result;
}

}  // namespace

MeshApproximation approximation(const FlintstoneTree3& tree, int level) {
  if (level < 0) throw InvalidInput("approximation level must be ≥ 0, got " + std::to_string(level));
  return approximate(tree, [&](const FlintstoneNode3& node) { return node.depth <= level; });
}

MeshApproximation adaptive_approximation(const FlintstoneTree3& tree, double max_error) {
  if (!(max_error >= 0.0)) throw InvalidInput("approximation error bound must be ≥ 0");
  return approximate(tree, [&](const FlintstoneNode3& node) { return node.stone.width() > max_error; });
}

PolygonApproximation approximation(const FlintstoneTree2& tree, int level) {
  if (level < 0) throw InvalidInput("approximation level must be ≥ 0, got " + std::to_string(level));
  return approximate(tree, [&](const FlintstoneNode2& node) { return node.depth <= level; });
}

PolygonApproximation adaptive_approximation(const FlintstoneTree2& tree, double max_error) {
  if (!(max_error >= 0.0)) throw InvalidInput("approximation error bound must be ≥ 0");
  return approximate(tree, [&](const FlintstoneNode2& node) { return node.stone.width() > max_error; });
}

}  // namespace scanstation
