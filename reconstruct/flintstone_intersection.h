// Intersection of two polygons / closed meshes through their flintstone
// trees (thesis §7.4): pairs of flintstones are tested by ball distances,
// only pairs that may meet are refined, and at the original edges/faces an
// exact test (CGAL Epick do_intersect) decides.
#pragma once

#include "reconstruct/flintstone_tree2.h"
#include "reconstruct/flintstone_tree3.h"

#include <array>
#include <cstddef>
#include <vector>

namespace scanstation {

struct IntersectionStats {
  std::size_t flintstone_tests = 0;  ///< flintstone pairs tested (§7.4 cases 1–3)
  std::size_t exact_tests = 0;       ///< edge/edge or face/face exact tests
};

/// Pairs (edge of a, edge of b) that intersect; edge k joins polygon vertices
/// k and k+1. Detection: `first_only` stops at the first pair found.
std::vector<std::array<int, 2>> intersecting_edges(const FlintstoneTree2& a, const FlintstoneTree2& b,
                                                   bool first_only = false, IntersectionStats* stats = nullptr);

/// Pairs (face of a, face of b) that intersect (touching counts), the same way.
std::vector<std::array<int, 2>> intersecting_faces(const FlintstoneTree3& a, const FlintstoneTree3& b,
                                                   bool first_only = false, IntersectionStats* stats = nullptr);

/// Do the solids bounded by the meshes intersect? Their surfaces meet, or one
/// contains the other (a vertex of one inside the other); the question CGAL's
/// Polygon_mesh_processing::do_intersect answers for closed meshes.
bool solids_intersect(const FlintstoneTree3& a, const FlintstoneTree3& b, IntersectionStats* stats = nullptr);

/// Brute-force references: every pair tested, sorted pairs.
std::vector<std::array<int, 2>> intersecting_edges_brute_force(const Eigen::MatrixX2d& a, const Eigen::MatrixX2d& b);
std::vector<std::array<int, 2>> intersecting_faces_brute_force(const TriangleMesh& a, const TriangleMesh& b);

}  // namespace scanstation
