// Hamiltonicity augmentation (thesis §5.4): when constriction of the
// Delaunay triangulation locks before every point is on the boundary, carve
// on with tetrahedra of γ([-1,1],[c0,1]), c0 < 0, lowering c0 step by step.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace scanstation {

struct AugmentationOptions {
  double step = 0.1;              ///< how much c0 drops per level
  double highest = -0.1;          ///< first level tried
  double lowest = -1.0;           ///< last level tried (γ([-1,1],[-1,1]) is complete)
  Eigen::MatrixXi keep;           ///< #K by 3 triangles never carved away (§5.7)
};

/// What augmentation did: the level that brought the last point to the
/// boundary (or the lowest tried) and how many tetrahedra it carved.
struct Augmentation {
  std::optional<double> c0_used;
  std::size_t carved = 0;
};

/// The Delaunay neighbours of every point in one array (compressed rows):
/// those of v are list[start[v] .. start[v + 1]). A vector per point costs
/// about twice the memory (growth slack and allocator headers), and
/// augmentation runs at the reconstruction's memory peak.
struct PointNeighbours {
  std::vector<int> start, list;
  std::span<const int> operator[](std::size_t v) const {
    return {list.data() + start[v], static_cast<std::size_t>(start[v + 1] - start[v])};
  }
};

/// points             #P by 3 positions (distinct)
/// adjacency          per point, its Delaunay neighbours (a point's candidates
///                    are the boundary triangles with a corner among them)
/// boundary           (in/out) #F by 3 closed, oriented, genus-0 surface,
///                    counter-clockwise seen from outside
/// interior_vertices  (in/out) points not yet on the boundary
///
/// A carve removes the tetrahedron (a, b, c, v) behind a boundary triangle
/// (a, b, c) and brings the interior point v to the boundary; allowed when
/// its three new triangles are in γ([-1,1],[c0,1]) (their symmetric lens
/// N_γ(c0,c0) holds no point, Lemma 3.3), no other point lies in the closed
/// tetrahedron, and no boundary triangle meets a new one except in shared
/// vertices or edges (the thesis deletes "the simplices that cross a removed
/// one"; here that is an exact intersection test). Then the boundary stays a
/// closed, simple, 2-manifold of genus 0. Among allowed carves the smallest
/// γ-indicator (Definition 5.2) goes first, as in constriction.
Augmentation augment_constriction(const Eigen::MatrixX3d& points, const PointNeighbours& adjacency,
                                  Eigen::MatrixX3i& boundary, std::vector<int>& interior_vertices,
                                  const AugmentationOptions& options = {});

}  // namespace scanstation

namespace scanstation {

/// The 2D counterpart (Figure 5.7): boundary is #B by 2 directed edges of a
/// counter-clockwise simple polygon (enclosed region on their left); a carve
/// removes the triangle (a, b, v) behind an edge (a, b) and brings the
/// interior point v onto the polygon, under the same γ([-1,1],[c0,1]),
/// emptiness and non-crossing conditions as in 3D.
Augmentation augment_constriction(const Eigen::MatrixX2d& points, const PointNeighbours& adjacency,
                                  Eigen::MatrixX2i& boundary, std::vector<int>& interior_vertices,
                                  const AugmentationOptions& options = {});

}  // namespace scanstation
