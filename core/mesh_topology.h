// Combinatorial checks of a triangle mesh: closed, manifold, oriented, genus.
#pragma once

#include "core/triangle_mesh.h"

#include <cstddef>
#include <optional>

namespace scanstation {

/// Counts and verdicts about the combinatorics of F (positions are not used).
struct MeshTopology {
  std::size_t vertices = 0;               ///< #V, referenced or not
  std::size_t isolated_vertices = 0;      ///< vertices no face references
  std::size_t faces = 0;                  ///< #F
  std::size_t edges = 0;                  ///< distinct undirected edges
  std::size_t boundary_edges = 0;         ///< edges with exactly one face
  std::size_t non_manifold_edges = 0;     ///< edges with three or more faces
  std::size_t non_manifold_vertices = 0;  ///< vertices whose faces form more than one fan
  std::size_t degenerate_faces = 0;       ///< faces repeating a vertex index
  std::size_t duplicate_faces = 0;        ///< faces on the same three vertices as an earlier face
  std::size_t components = 0;             ///< connected components of faces (through shared vertices)
  std::size_t boundary_loops = 0;         ///< connected components of boundary edges
  long long euler_characteristic = 0;     ///< V' - E + F over referenced vertices V'

  bool closed = false;      ///< faces exist and every edge has exactly two faces
  bool manifold = false;    ///< no non-manifold edge or vertex, no degenerate or duplicate face
  bool oriented = false;    ///< manifold and every interior edge is used once in each direction
  bool orientable = false;  ///< manifold and some choice of face orientations is consistent
  /// For an orientable manifold: Σ over components of g, from
  /// χ = 2C − 2g − (boundary loops). nullopt otherwise.
  std::optional<long long> genus;
};

/// Inspects F (#F by 3 indices into #V vertices). Indices must lie in
/// [0, #V) (the readers guarantee it); throws InvalidInput otherwise.
MeshTopology mesh_topology(const Eigen::MatrixX3i& F, Eigen::Index vertex_count);

/// Throws InvalidInput unless every index of F lies in [0, vertex_count)
/// (mesh_topology's first check).
void require_face_indices(const Eigen::MatrixX3i& F, Eigen::Index vertex_count);

inline MeshTopology mesh_topology(const TriangleMesh& mesh) {
  return mesh_topology(mesh.faces, mesh.vertex_count());
}

}  // namespace scanstation
