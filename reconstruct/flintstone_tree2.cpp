#include "reconstruct/flintstone_tree2.h"

#include "core/errors.h"
#include "reconstruct/smallest_enclosing_ball.h"

#include <algorithm>

namespace scanstation {

namespace {

/// A node slot: a fresh one, or one released by a rebuilt subtree.
int allocate(FlintstoneTree2& tree) {
  if (tree.free_nodes.empty()) {
    tree.nodes.emplace_back();
    return static_cast<int>(tree.nodes.size() - 1);
  }
  const int id = tree.free_nodes.back();
  tree.free_nodes.pop_back();
  return id;
}

/// Splits chain p … s (s ≥ p + 2) into node `id` and, iteratively, all its
/// descendants (Algorithm 7.1's loop, depth first instead of level by level:
/// the tree is the same).
void build_chain(FlintstoneTree2& tree, int id, int p, int s, int depth) {
  struct Task {
    int id, p, s, depth;
  };
  std::vector<Task> tasks{{id, p, s, depth}};
  std::vector<int> members;
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    members.clear();
    for (int k = task.p + 1; k < task.s; ++k) members.push_back(tree.vertex(k));
    int split = -1;
    FlintstoneNode2 node;
    node.p = task.p;
    node.s = task.s;
    node.depth = task.depth;
    node.stone = flintstone_of<2>(tree.vertices, {tree.vertex(task.p), tree.vertex(task.s)}, members, split);
    // flintstone_of names a vertex; a polygon may visit the same position
    // twice, so take the first position holding it. Where the vertices after
    // it repeat its coordinates (they tie with it), split in the middle of
    // that run, and in the middle of the chain when no vertex was named (its
    // ends coincide): splitting at one end made a chain of n copies of one
    // point n levels deep, O(n²) to build (100k copies did not finish).
    node.q = (task.p + task.s) / 2;
    for (int k = task.p + 1; k < task.s && split >= 0; ++k)
      if (tree.vertex(k) == split) {
        int last = k;
        while (last + 1 < task.s && tree.vertices.row(tree.vertex(last + 1)) == tree.vertices.row(split)) ++last;
        node.q = k + (last - k) / 2;
        break;
      }
    for (int side = 0; side < 2; ++side) {
      const int a = side == 0 ? node.p : node.q, b = side == 0 ? node.q : node.s;
      if (b - a < 2) continue;
      node.child[side] = allocate(tree);
      tasks.push_back({node.child[side], a, b, task.depth + 1});
    }
    tree.nodes[static_cast<std::size_t>(task.id)] = node;
  }
}

/// Node id of a new tree for chain p … s, or -1 for an edge.
int new_chain(FlintstoneTree2& tree, int p, int s, int depth) {
  if (s - p < 2) return -1;
  const int id = allocate(tree);
  build_chain(tree, id, p, s, depth);
  return id;
}

void release_subtree(FlintstoneTree2& tree, int id) {
  std::vector<int> stack{id};
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    if (n < 0) continue;
    tree.free_nodes.push_back(n);
    for (const int c : tree.nodes[static_cast<std::size_t>(n)].child) stack.push_back(c);
  }
}

}  // namespace

int FlintstoneTree2::levels() const {
  int deepest = 0;
  std::vector<int> stack(top.begin(), top.end());
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    if (id < 0) continue;
    deepest = std::max(deepest, nodes[static_cast<std::size_t>(id)].depth);
    for (const int c : nodes[static_cast<std::size_t>(id)].child) stack.push_back(c);
  }
  return deepest + 1;
}

std::size_t FlintstoneTree2::storage_bytes() const {
  return static_cast<std::size_t>(live_nodes()) * sizeof(FlintstoneNode2) + sizeof(FlintstoneTree2);
}

FlintstoneTree2 flintstone_tree(const Polygon2& polygon) {
  const int n = static_cast<int>(polygon.size());
  if (n < 3) throw InvalidInput("flintstone tree: a polygon needs at least 3 vertices, got " + std::to_string(n));
  require_ball_range<2>(polygon.vertices, "polygon");
  FlintstoneTree2 tree;
  tree.vertices = polygon.vertices;
  // Smallest bounding disc; its two touching vertices farthest apart give the
  // zeroth-order edge (§7.2.2).
  const EnclosingBall<2> disc = smallest_enclosing_ball<2>(tree.vertices);
  if (disc.support.size() < 2 || disc.radius <= 0.0)
    throw InvalidInput("flintstone tree: all " + std::to_string(n) + " polygon vertices coincide");
  double farthest = -1.0;
  for (std::size_t a = 0; a < disc.support.size(); ++a)
    for (std::size_t b = a + 1; b < disc.support.size(); ++b) {
      const double d = (tree.vertices.row(disc.support[a]) - tree.vertices.row(disc.support[b])).squaredNorm();
      if (d > farthest) {
        farthest = d;
        tree.first = std::min(disc.support[a], disc.support[b]);
        tree.second = std::max(disc.support[a], disc.support[b]);
      }
    }
  if (tree.first == tree.second) throw InvalidInput("flintstone tree: the bounding disc touches a single vertex");
  const double reach = (tree.vertices.rowwise() - disc.center.transpose()).rowwise().norm().maxCoeff();
  tree.root = ball_flintstone<2>(disc.center, std::max(disc.radius, reach));
  tree.nodes.reserve(static_cast<std::size_t>(n));
  tree.top[0] = new_chain(tree, tree.first, tree.second, 1);
  tree.top[1] = new_chain(tree, tree.second, tree.first + n, 1);
  return tree;
}

int insert_vertex(FlintstoneTree2& tree, int index, const Eigen::Vector2d& point) {
  const int n = tree.size();
  if (index < 0 || index > n)
    throw InvalidInput("insert_vertex: index " + std::to_string(index) + " outside [0, " + std::to_string(n) + "]");
  Eigen::MatrixX2d grown(n + 1, 2);
  grown.topRows(index) = tree.vertices.topRows(index);
  grown.row(index) = point.transpose();
  grown.bottomRows(n - index) = tree.vertices.bottomRows(n - index);
  if (!tree.root.contains(point)) {  // outside the bounding disc: a new root
    tree = flintstone_tree(Polygon2{grown});
    return n + 1;
  }
  // Renumber the unrolled positions for the new vertex count.
  const auto renumber = [&](int position) {
    const int wrap = position / n, v = position % n;
    return wrap * (n + 1) + v + (v >= index ? 1 : 0);
  };
  tree.vertices = grown;
  tree.first = renumber(tree.first);
  tree.second = renumber(tree.second);
  for (FlintstoneNode2& node : tree.nodes) {
    node.p = renumber(node.p);
    node.q = renumber(node.q);
    node.s = renumber(node.s);
  }
  // The new vertex's unrolled position inside exactly one top chain.
  int at = index;
  std::array<Chain2, 2> tops = tree.top_chains();
  int side = at > tops[0].p && at < tops[0].s ? 0 : 1;
  if (side == 1 && at <= tops[1].p) at += n + 1;
  // Walk down while the flintstones still contain the new vertex.
  int parent = -1, parent_side = side;
  Chain2 chain = tops[static_cast<std::size_t>(side)];
  while (chain.node >= 0) {
    const FlintstoneNode2& node = tree.nodes[static_cast<std::size_t>(chain.node)];
    if (!node.stone.contains(point)) break;
    parent = chain.node;
    parent_side = at < node.q ? 0 : 1;
    chain = tree.children(node)[static_cast<std::size_t>(parent_side)];
  }
  // Rebuild the subtree of that chain (an original edge v_p v_s has become
  // v_p v_new v_s and gets its first node).
  const int depth = parent < 0 ? 1 : tree.nodes[static_cast<std::size_t>(parent)].depth + 1;
  if (chain.node >= 0) release_subtree(tree, chain.node);
  const int id = new_chain(tree, chain.p, chain.s, depth);
  (parent < 0 ? tree.top : tree.nodes[static_cast<std::size_t>(parent)].child)[static_cast<std::size_t>(parent_side)] =
      id;
  return chain.s - chain.p - 1;
}

}  // namespace scanstation
