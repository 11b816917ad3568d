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

#include <cstddef>

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

/// The same answer by testing every face of the closed mesh (V, F).
bool inside_brute_force(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::Vector3d& x);

}  // namespace scanstation
