#include "reconstruct/flintstone_approximation.h"

#include "core/errors.h"

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

}  // namespace

PolygonApproximation approximation(const FlintstoneTree2& tree, int level) {
  if (level < 0) throw InvalidInput("approximation level must be ≥ 0, got " + std::to_string(level));
  return approximate(tree, [&](const FlintstoneNode2& node) { return node.depth <= level; });
}

PolygonApproximation adaptive_approximation(const FlintstoneTree2& tree, double max_error) {
  if (!(max_error >= 0.0)) throw InvalidInput("approximation error bound must be ≥ 0");
  return approximate(tree, [&](const FlintstoneNode2& node) { return node.stone.width() > max_error; });
}

}  // namespace scanstation
