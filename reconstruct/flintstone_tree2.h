// The 2D flintstone tree of a closed polygon (thesis §7.2.2, Algorithm 7.1)
// and dynamic insertion of a vertex (§7.5).
#pragma once

#include "core/polygon.h"
#include "reconstruct/flintstone.h"

#include <array>
#include <cstddef>
#include <vector>

namespace scanstation {

/// A polyline v_p … v_s of the polygon. Positions are "unrolled": p < s, and
/// position k stands for vertex k mod N, so the chain that wraps past vertex
/// N−1 needs no special case.
struct Chain2 {
  int p = 0;
  int s = 0;
  int node = -1;  ///< the node that splits it, -1 for an original edge (s = p + 1)
};

/// A node of the binary flintstone tree: the vertex v_q it adds to the
/// approximation of chain v_p … v_s, and F(v_p … v_s) (Definition 7.3).
struct FlintstoneNode2 {
  int p = 0, q = 0, s = 0;  ///< unrolled positions, p < q < s
  int depth = 1;            ///< approximation level at which v_q appears
  std::array<int, 2> child = {-1, -1};  ///< nodes of chains p…q and q…s (-1: an edge)
  Flintstone<2> stone;
};

/// Root: the smallest bounding disc and the zeroth-order edge v_i v_j (i < j)
/// between the two touching vertices farthest apart; top[0] splits chain
/// v_i … v_j, top[1] chain v_j … v_{i+N}. In-order traversal yields the polygon.
struct FlintstoneTree2 {
  Eigen::MatrixX2d vertices;
  Flintstone<2> root;
  int first = 0, second = 0;
  std::array<int, 2> top = {-1, -1};
  std::vector<FlintstoneNode2> nodes;  ///< N − 2 live nodes (Theorem 7.2)
  std::vector<int> free_nodes;         ///< slots released by rebuilt subtrees

  int size() const { return static_cast<int>(vertices.rows()); }
  int vertex(int position) const { return position % size(); }
  Eigen::Vector2d point(int position) const { return vertices.row(vertex(position)).transpose(); }
  std::array<Chain2, 2> top_chains() const {
    return {Chain2{first, second, top[0]}, Chain2{second, first + size(), top[1]}};
  }
  /// The two sub-chains of a node's chain.
  std::array<Chain2, 2> children(const FlintstoneNode2& n) const {
    return {Chain2{n.p, n.q, n.child[0]}, Chain2{n.q, n.s, n.child[1]}};
  }
  int live_nodes() const { return static_cast<int>(nodes.size() - free_nodes.size()); }
  /// Number of approximation levels; the finest (the polygon) is levels() − 1.
  int levels() const;
  std::size_t storage_bytes() const;
};

/// Builds the complete tree (Algorithm 7.1). The smallest bounding disc is
/// CGAL's Min_circle_2 (expected linear time, Welgl's algorithm).
/// Throws InvalidInput for fewer than 3 vertices or all vertices equal.
FlintstoneTree2 flintstone_tree(const Polygon2& polygon);

/// Inserts `point` as polygon vertex number `index` (between the old vertices
/// index−1 and index) and adapts the tree as §7.5 says: the first flintstone on
/// the way down that does not contain the point has its subtree rebuilt (the
/// whole tree when it leaves the bounding disc). Returns the number of vertices
/// whose subtree was rebuilt.
int insert_vertex(FlintstoneTree2& tree, int index, const Eigen::Vector2d& point);

}  // namespace scanstation
