#include "reconstruct/flintstone_intersection.h"

#include "reconstruct/flintstone_inclusion.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>

namespace scanstation {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_2 cgal(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }
Kernel::Point_3 cgal(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

bool segments_intersect(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                        const Eigen::Vector2d& b1) {
  return CGAL::do_intersect(Kernel::Segment_2(cgal(a0), cgal(a1)), Kernel::Segment_2(cgal(b0), cgal(b1)));
}

/// Exact triangle/triangle test; a flat (collinear) triangle is tested as
/// its segments, since CGAL's test needs proper triangles.
bool triangles_intersect(const std::array<Eigen::Vector3d, 3>& a, const std::array<Eigen::Vector3d, 3>& b) {
  const Kernel::Triangle_3 ta(cgal(a[0]), cgal(a[1]), cgal(a[2])), tb(cgal(b[0]), cgal(b[1]), cgal(b[2]));
  const bool flat_a = ta.is_degenerate(), flat_b = tb.is_degenerate();
  if (!flat_a && !flat_b) return CGAL::do_intersect(ta, tb);
  const auto segment = [](const std::array<Eigen::Vector3d, 3>& t, int k) {
    return Kernel::Segment_3(cgal(t[static_cast<std::size_t>(k)]), cgal(t[static_cast<std::size_t>((k + 1) % 3)]));
  };
  for (int i = 0; i < 3; ++i) {
    if (flat_a && !flat_b && !segment(a, i).is_degenerate() && CGAL::do_intersect(segment(a, i), tb)) return true;
    if (flat_b && !flat_a && !segment(b, i).is_degenerate() && CGAL::do_intersect(segment(b, i), ta)) return true;
    if (flat_a && flat_b)
      for (int j = 0; j < 3; ++j) {
        const auto sa = segment(a, i), sb = segment(b, j);
        if (sa.is_degenerate() || sb.is_degenerate() ? sa.source() == sb.source() : CGAL::do_intersect(sa, sb))
          return true;
      }
  }
  return false;
}

std::array<Eigen::Vector3d, 3> triangle(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, int f) {
  return {V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(), V.row(F(f, 2)).transpose()};
}

/// The flintstone of a chain; an original edge gets the disc around it.
Flintstone<2> chain_stone(const FlintstoneTree2& tree, const Chain2& chain) {
  if (chain.node >= 0) return tree.nodes[static_cast<std::size_t>(chain.node)].stone;
  const Eigen::Vector2d a = tree.point(chain.p), b = tree.point(chain.s);
  return ball_flintstone<2>(0.5 * (a + b), 0.5 * (b - a).norm());
}

/// §7.4: refine the bigger of a pair of meeting flintstones until both are
/// original pieces, then test exactly. `Item` is a tree position, `split`
/// lists its children into its third argument (none for an original piece),
/// `size` orders refinement, `meet` tests their bounding volumes, `exact`
/// tests two leaves.
template <typename Item, typename Split, typename Size, typename Meet, typename Exact>
void traverse_pairs(std::vector<std::pair<Item, Item>> stack, const Split& split, const Size& size,
                    const Meet& meet, const Exact& exact, bool first_only, IntersectionStats& count) {
  std::vector<Item> children_a, children_b;
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    ++count.flintstone_tests;
    if (!meet(a, b)) continue;
    split(a, 0, children_a);
    split(b, 1, children_b);
    if (children_a.empty() && children_b.empty()) {
      ++count.exact_tests;
      if (exact(a, b) && first_only) return;
      continue;
    }
    if (!children_a.empty() && (children_b.empty() || size(a, 0) >= size(b, 1))) {
      for (const Item& child : children_a) stack.push_back({child, b});
    } else {
      for (const Item& child : children_b) stack.push_back({a, child});
    }
  }
}

void sort_unique(std::vector<std::array<int, 2>>& pairs) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

}  // namespace

std::vector<std::array<int, 2>> intersecting_edges(const FlintstoneTree2& a, const FlintstoneTree2& b, bool first_only,
                                                   IntersectionStats* stats) {
  IntersectionStats local;
  IntersectionStats& count = stats ? *stats : local;
  std::vector<std::array<int, 2>> pairs;
  ++count.flintstone_tests;
  if (!flintstones_meet(a.root, b.root)) return pairs;
  const std::array<const FlintstoneTree2*, 2> trees = {&a, &b};
  const auto split = [&](const Chain2& chain, int t, std::vector<Chain2>& children) {
    children.clear();
    if (chain.node < 0) return;
    const FlintstoneTree2& tree = *trees[static_cast<std::size_t>(t)];
    for (const Chain2& child : tree.children(tree.nodes[static_cast<std::size_t>(chain.node)])) children.push_back(child);
  };
  const auto size = [](const Chain2& chain, int) { return chain.s - chain.p; };
  const auto meet = [&](const Chain2& ca, const Chain2& cb) {
    return flintstones_meet(chain_stone(a, ca), chain_stone(b, cb));
  };
  const auto exact = [&](const Chain2& ea, const Chain2& eb) {
    if (!segments_intersect(a.point(ea.p), a.point(ea.s), b.point(eb.p), b.point(eb.s))) return false;
    pairs.push_back({a.vertex(ea.p), b.vertex(eb.p)});
    return true;
  };
  std::vector<std::pair<Chain2, Chain2>> stack;
  for (const Chain2& ca : a.top_chains())
    for (const Chain2& cb : b.top_chains()) stack.push_back({ca, cb});
  traverse_pairs(stack, split, size, meet, exact, first_only, count);
  sort_unique(pairs);
  return pairs;
}

std::vector<std::array<int, 2>> intersecting_faces(const FlintstoneTree3& a, const FlintstoneTree3& b, bool first_only,
                                                   IntersectionStats* stats) {
  IntersectionStats local;
  IntersectionStats& count = stats ? *stats : local;
  std::vector<std::array<int, 2>> pairs;
  const std::array<const FlintstoneTree3*, 2> trees = {&a, &b};
  const auto node = [&](int id, int t) -> const FlintstoneNode3& {
    return trees[static_cast<std::size_t>(t)]->nodes[static_cast<std::size_t>(id)];
  };
  const auto split = [&](int id, int t, std::vector<int>& children) {
    children.clear();
    for (int c = 0; c < node(id, t).child_count; ++c) children.push_back(node(id, t).first_child + c);
  };
  const auto size = [&](int id, int t) { return node(id, t).face_count; };
  // F(P) ∩ bound ∩ box localizes each node (see FlintstoneNode3::bound, box).
  const auto meet = [&](int na, int nb) {
    return node(na, 0).box.intersects(node(nb, 1).box) && balls_meet(node(na, 0).bound, node(nb, 1).bound) &&
           flintstones_meet(node(na, 0).stone, node(nb, 1).stone);
  };
  const auto exact = [&](int na, int nb) {
    const int fa = a.face_order[static_cast<std::size_t>(node(na, 0).first_face)];
    const int fb = b.face_order[static_cast<std::size_t>(node(nb, 1).first_face)];
    if (!triangles_intersect(triangle(a.vertices, a.faces, fa), triangle(b.vertices, b.faces, fb))) return false;
    pairs.push_back({fa, fb});
    return true;
  };
  traverse_pairs<int>({{0, 0}}, split, size, meet, exact, first_only, count);
  sort_unique(pairs);
  return pairs;
}

bool solids_intersect(const FlintstoneTree3& a, const FlintstoneTree3& b, IntersectionStats* stats) {
  if (!intersecting_faces(a, b, true, stats).empty()) return true;
  // Disjoint surfaces: the solids meet only if one holds the other entirely.
  return inside(b, a.vertices.row(a.faces(0, 0)).transpose()) || inside(a, b.vertices.row(b.faces(0, 0)).transpose());
}

std::vector<std::array<int, 2>> intersecting_edges_brute_force(const Eigen::MatrixX2d& a, const Eigen::MatrixX2d& b) {
  std::vector<std::array<int, 2>> pairs;
  for (int i = 0; i < a.rows(); ++i)
    for (int j = 0; j < b.rows(); ++j)
      if (segments_intersect(a.row(i).transpose(), a.row((i + 1) % a.rows()).transpose(), b.row(j).transpose(),
                             b.row((j + 1) % b.rows()).transpose()))
        pairs.push_back({i, j});
  return pairs;
}

std::vector<std::array<int, 2>> intersecting_faces_brute_force(const TriangleMesh& a, const TriangleMesh& b) {
  std::vector<std::array<int, 2>> pairs;
  for (int i = 0; i < a.face_count(); ++i)
    for (int j = 0; j < b.face_count(); ++j)
      if (triangles_intersect(triangle(a.vertices.positions, a.faces, i), triangle(b.vertices.positions, b.faces, j)))
        pairs.push_back({i, j});
  return pairs;
}

}  // namespace scanstation
