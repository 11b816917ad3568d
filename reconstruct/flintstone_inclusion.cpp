#include "reconstruct/flintstone_inclusion.h"

#include "core/predicates.h"

#include <algorithm>

namespace scanstation {

namespace {

enum class Crossing { none, once, on_boundary };

/// Does the ray from x along +x cross segment a b? Half-open in y (an end
/// point exactly at x's height counts only for the edge going up from it),
/// decided by an exact orientation.
Crossing ray_crossing(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& x) {
  const int o = orientation(a, b, x);
  if (o == 0 && x.x() >= std::min(a.x(), b.x()) && x.x() <= std::max(a.x(), b.x()) &&
      x.y() >= std::min(a.y(), b.y()) && x.y() <= std::max(a.y(), b.y()))
    return Crossing::on_boundary;
  if ((a.y() > x.y()) == (b.y() > x.y())) return Crossing::none;
  return (b.y() > x.y() ? o > 0 : o < 0) ? Crossing::once : Crossing::none;
}

}  // namespace

bool inside(const FlintstoneTree2& tree, const Eigen::Vector2d& x, InclusionStats* stats) {
  InclusionStats local;
  InclusionStats& count = stats ? *stats : local;
  ++count.flintstone_tests;
  if (!tree.root.contains(x)) return false;  // outside the bounding disc
  bool odd = false;
  std::vector<Chain2> stack;
  const auto tops = tree.top_chains();
  stack.assign(tops.begin(), tops.end());
  while (!stack.empty()) {
    const Chain2 chain = stack.back();
    stack.pop_back();
    const Eigen::Vector2d a = tree.point(chain.p), b = tree.point(chain.s);
    if (chain.node >= 0) {
      const FlintstoneNode2& node = tree.nodes[static_cast<std::size_t>(chain.node)];
      ++count.flintstone_tests;
      // Lemma 6.1: outside F(v_p … v_s) the edge v_p v_s answers for the chain
      // (it lies in both balls, which are convex; a union flintstone, only
      // possible for degenerate input, is always refined).
      if (node.stone.is_union || node.stone.contains(x) || orientation(a, b, x) == 0) {
        const auto children = tree.children(node);
        stack.insert(stack.end(), children.begin(), children.end());
        continue;
      }
    }
    ++count.crossing_tests;
    const Crossing crossing = ray_crossing(a, b, x);
    if (crossing == Crossing::on_boundary) return true;
    if (crossing == Crossing::once) odd = !odd;
  }
  return odd;
}

bool inside_brute_force(const Eigen::MatrixX2d& V, const Eigen::Vector2d& x) {
  bool odd = false;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Crossing crossing = ray_crossing(V.row(i).transpose(), V.row((i + 1) % V.rows()).transpose(), x);
    if (crossing == Crossing::on_boundary) return true;
    if (crossing == Crossing::once) odd = !odd;
  }
  return odd;
}

}  // namespace scanstation
