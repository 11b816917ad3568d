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

#include <cstddef>

namespace scanstation {

/// What a hierarchical query touched (summed over queries).
struct InclusionStats {
  std::size_t flintstone_tests = 0;  ///< point-in-flintstone tests
  std::size_t crossing_tests = 0;    ///< exact edge/triangle crossing tests
};

/// True when x lies inside the polygon or on its boundary. Half-open ray
/// rule along +x, so no crossing needs a second try.
bool inside(const FlintstoneTree2& tree, const Eigen::Vector2d& x, InclusionStats* stats = nullptr);

/// The same answer by testing every edge of the polygon V (#V by 2).
bool inside_brute_force(const Eigen::MatrixX2d& V, const Eigen::Vector2d& x);

}  // namespace scanstation
