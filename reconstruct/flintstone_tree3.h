// The 3D flintstone tree of a closed genus-0 triangle mesh (thesis §7.3,
// Algorithm 7.2).
//
// Every node stands for an open polyhedron P: a connected set of original
// faces whose boundary runs along shortest edge paths (Dijkstra) between its
// three corners v_p, v_s, v_t; the triangle v_p v_s v_t approximates P, and
// F(P) (Definition 7.5) bounds it. Refinement splits P along shortest paths:
// a three-split at the vertex v_q / v_r of Algorithm 7.2, or side splits at
// the path vertex that best balances the two new sides when a corner angle is
// below the angle threshold (§7.3.2) or when P has no interior vertex. The
// faces of a child are the connected components the cut paths leave, so
// void triangles (coalescing paths) never become nodes, and the leaves are
// exactly the original faces.
#pragma once

#include "core/triangle_mesh.h"
#include "reconstruct/flintstone.h"

#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <vector>

namespace scanstation {

struct FlintstoneNode3 {
  std::array<int, 3> corners = {0, 0, 0};  ///< v_p, v_s, v_t in the orientation of the faces
  int depth = 0;                           ///< the root (the whole mesh) is 0
  int first_face = 0, face_count = 0;      ///< range of FlintstoneTree3::face_order
  int first_boundary = 0, boundary_count = 0;  ///< range of FlintstoneTree3::boundary
  int first_child = 0, child_count = 0;        ///< children are consecutive nodes
  /// F(P); for a leaf (one original face) the ball around it, used by pair tests.
  Flintstone<3> stone;
  /// A ball around P's vertices (centroid, farthest vertex). Not in the
  /// thesis: a union flintstone (Definition 7.2) can be far larger than P,
  /// so the operations localize by F(P) ∩ bound ∩ box — still a bounding volume,
  /// and convex whenever F(P) is an intersection.
  SignedBall<3> bound;
  /// The axis-aligned box of P's vertices, widened by a relative slack. Not
  /// in the thesis either: it is convex and holds P and the fan over its
  /// boundary, so it may join the localizing volume (Lemma 6.1 needs only a
  /// volume that holds both) and it is the cheapest test against a ray.
  Eigen::AlignedBox3d box;

  bool leaf() const { return child_count == 0; }
};

/// How the tree splits (§7.3.2).
struct FlintstoneOptions3 {
  /// Corner angles (radians) below this are not split by a three-split; the
  /// triangle is split at its sides instead. 0 disables side splits by angle.
  double angle_threshold = 0.35;
};

/// Counts of the split kinds used while building.
struct FlintstoneBuildStats3 {
  std::size_t three_splits = 0;
  std::size_t side_splits = 0;
  std::size_t fallback_splits = 0;  ///< paths left one piece: split by breadth-first halves
};

struct FlintstoneTree3 {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  std::vector<FlintstoneNode3> nodes;      ///< nodes[0] is the root: the bounding ball through 3 vertices
  std::vector<int> face_order;             ///< faces of every node are one range of this permutation
  std::vector<std::array<int, 2>> boundary;  ///< directed boundary edges of the nodes' open polyhedra
  FlintstoneBuildStats3 stats;
  FlintstoneOptions3 options;

  const FlintstoneNode3& root() const { return nodes.front(); }
  /// Ids of the nodes in the tree (insert_vertex leaves replaced ones behind).
  std::vector<int> reachable() const;
  /// Number of approximation levels; the finest (the mesh) is levels() − 1.
  int levels() const;
  std::size_t storage_bytes() const;
};

/// Builds the complete tree. The mesh must be closed, manifold and oriented
/// (genus 0 is what the thesis assumes; other genera still give a valid
/// localization tree). Throws TopologyError otherwise, InvalidInput for a
/// mesh without faces or with all vertices on one line.
FlintstoneTree3 flintstone_tree(const TriangleMesh& mesh, const FlintstoneOptions3& options = {});

/// Dynamic insertion (§7.5): splits `face` into three around the new vertex
/// `point` (it becomes the last vertex; the face keeps its index for one of
/// the three, the other two are appended), then rebuilds the subtree of the
/// first node on the way down to the face whose volume F(P) ∩ bound no longer
/// holds the point (the whole tree when it leaves the root ball). Returns the
/// number of faces of the rebuilt subtree. The face neighbourhood table is
/// recomputed (linear time); the tree work is local.
int insert_vertex(FlintstoneTree3& tree, int face, const Eigen::Vector3d& point);

}  // namespace scanstation
