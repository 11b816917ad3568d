// Point inclusion, hierarchically through a flintstone tree (thesis §6.1,
// Lemma 6.1, and §7.4), and the brute-force ray-parity reference.
//
// Both answer exactly (CGAL's exact predicates decide every crossing): a point
// on the boundary counts as inside. The hierarchical test replaces a part B of
// the boundary by its approximation A whenever the query point lies outside a
// flintstone holding A and B (Lemma 6.1), so a crossing with A counts for
// all crossings with B.
#pragma once

#include "reconstruct/flintstone_tree2.h"
#include "reconstruct/flintstone_tree3.h"

#include <array>
#include <cstddef>
#include <vector>

namespace scanstation {

/// What a hierarchical query touched (summed over queries).
struct InclusionStats {
  std::size_t flintstone_tests = 0;  ///< point-in-flintstone tests
  std::size_t crossing_tests = 0;    ///< exact edge/triangle crossing tests
  std::size_t replacements = 0;      ///< parts answered by their approximation (Lemma 6.1)
};

/// True when x lies inside the polygon or on its boundary. Half-open ray
/// rule along +x, so no crossing needs a second try.
bool inside(const FlintstoneTree2& tree, const Eigen::Vector2d& x, InclusionStats* stats = nullptr);

/// The same answer by testing every edge of the polygon V (#V by 2).
bool inside_brute_force(const Eigen::MatrixX2d& V, const Eigen::Vector2d& x);

/// True when x lies inside the closed mesh of the tree or on it. The ray is
/// the segment from x to a far point in a fixed sequence of directions; a
/// direction that passes exactly through an edge or vertex of a tested
/// triangle (or lies in its plane) is replaced by the next one. A node's
/// open polyhedron is replaced (Lemma 6.1) by the fan from its first corner
/// over its boundary edges: the same boundary, so no cracks, and inside the
/// node's volume F(P) ∩ box (convex when the flintstone is an intersection of
/// balls; the box alone for a union). Nodes whose volume the ray misses are
/// skipped (their faces lie in it); a fan is used
/// only while it is short (≤ 4 edges): measured on real meshes, refining a
/// node the ray hits is cheaper than testing a long fan.
bool inside(const FlintstoneTree3& tree, const Eigen::Vector3d& x, InclusionStats* stats = nullptr);

/// A flintstone tree packed for many inclusion queries (Lemma 6.1, §7.4):
/// built once from a FlintstoneTree3, answers exactly what inside(tree, x)
/// answers with fewer and cheaper node visits.
///  - Nodes are laid out depth first, each with the index just past its
///    subtree (`skip`), so a query is one forward sweep without a stack, and
///    hold only what the sweep reads on every visit: the box, rounded
///    outwards to float (32 bytes a node: two per cache line), the skip and
///    the first of the node's triangles. Its triangles are its face for a
///    leaf, the fan over its boundary for an inner node with a short
///    boundary (Lemma 6.1), coordinates copied in so a crossing test reads
///    one record; an inner node's triangles end where its first child's
///    begin. The lens F(P) (an index into `lenses`; none for a union
///    flintstone or where it is never used) is kept beside the nodes.
///  - Chains are collapsed: an inner node whose box is nearly its parent's
///    prunes little, so its children are attached to the parent instead
///    (the parent's volume still holds them; only a chance to use the
///    node's fan is lost).
struct FlintstoneInclusion3 {
  struct Node {
    /// The box that holds the node's faces and its fan, as min, −max, each
    /// rounded down to a float (so the float box holds the exact one): an
    /// axis-aligned segment misses it when any of these exceeds the
    /// segment's max, −min rounded up (at most six comparisons, exact).
    std::array<float, 6> bounds{};
    int skip = 0;            ///< the next node after this one's subtree
    int first_triangle = 0;  ///< a leaf's face, or the fan (an inner node without one: always refined)

    bool leaf(int self) const { return skip == self + 1; }
    Eigen::AlignedBox3d box() const {
      return {Eigen::Vector3d(bounds[0], bounds[1], bounds[2]), Eigen::Vector3d(-bounds[3], -bounds[4], -bounds[5])};
    }
  };
  struct Lens {
    Eigen::Vector3d first_center, second_center;
    double first_radius = 0.0, second_radius = 0.0;
  };
  std::vector<Node> nodes;  ///< nodes[0] is the root (the whole mesh)
  /// lens_of[k] of a node the packing added above many children: a box
  /// only, no flintstone.
  static constexpr int sorting_node = -2;
  std::vector<int> lens_of;  ///< per node: F(P) = lenses[k].first ∩ .second; -1: the box only
  std::vector<Lens> lenses;
  std::vector<std::array<Eigen::Vector3d, 3>> triangles;
  Eigen::AlignedBox3d box;  ///< the root's exact box (the first ray's length)
  SignedBall<3> root_ball;  ///< the root flintstone
  Eigen::MatrixX3d vertices;  ///< the mesh, for the last-resort brute force
  Eigen::MatrixX3i faces;

  /// Triangles of node k: one for a leaf, the fan (maybe none) for an inner node.
  int triangle_count(int k) const {
    return nodes[static_cast<std::size_t>(k)].leaf(k)
               ? 1
               : nodes[static_cast<std::size_t>(k) + 1].first_triangle - nodes[static_cast<std::size_t>(k)].first_triangle;
  }
  std::size_t storage_bytes() const;
};

/// Packs `tree` for queries (linear time).
FlintstoneInclusion3 inclusion_index(const FlintstoneTree3& tree);

/// The answer of inside(tree, x) for the tree the index was built from.
bool inside(const FlintstoneInclusion3& index, const Eigen::Vector3d& x, InclusionStats* stats = nullptr);

/// The same answer by testing every face of the closed mesh (V, F).
bool inside_brute_force(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::Vector3d& x);

}  // namespace scanstation
