// Hamiltonicity augmentation (thesis §5.4): when constriction of the
// Delaunay triangulation locks before every point is on the boundary, carve
// on with tetrahedra of γ([-1,1],[c0,1]), c0 < 0, lowering c0 step by step.
#pragma once

#include "reconstruct/delaunay_complex.h"

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

namespace scanstation {

class BoundarySurface;
class PointTree;

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

/// The Delaunay neighbours of the points. Only the cells around each point
/// are indexed up front (a counting sort); a point's neighbours are listed
/// when first asked for, in the order of the cells around it. Augmentation
/// asks for those of the points constriction left inside and of the points
/// near its carves: listing every point's neighbours in advance took longer
/// than augmentation itself on CGAL's meshes.
class PointNeighbours {
 public:
  explicit PointNeighbours(const DelaunayComplex<2>& dt);
  explicit PointNeighbours(const DelaunayComplex<3>& dt);
  /// With the cells around each point of dt shared with other steps: built
  /// here if `around` is empty; it must outlive this object.
  PointNeighbours(const DelaunayComplex<3>& dt, std::optional<CellsAround>& around);
  PointNeighbours(const PointNeighbours&) = delete;
  PointNeighbours& operator=(const PointNeighbours&) = delete;
  /// Valid as long as this object lives.
  std::span<const int> operator[](std::size_t v) const;

 private:
  template <typename Cells>
  PointNeighbours(const Cells& cells, std::optional<CellsAround> own, const CellsAround* shared);

  const int* vertices_ = nullptr;  // the complex's cell matrix, read in place
  std::ptrdiff_t cell_step_ = 0, vertex_step_ = 0;
  int per_cell_ = 0;
  std::optional<CellsAround> own_around_;  // unless shared
  const CellsAround* cells_around_;
  mutable std::unordered_map<std::size_t, std::vector<int>> lists_;  // node-based: spans stay valid
  mutable std::vector<std::size_t> seen_;  // per point: 1 + the point whose list saw it last
};

/// points             #P by 3 positions (distinct)
/// adjacency          per point, its Delaunay neighbours (a point's candidates
///                    are the boundary triangles with a corner among them)
/// boundary           (in/out) #F by 3 closed, oriented, genus-0 surface,
///                    counter-clockwise seen from outside
/// interior_vertices  (in/out) points not yet on the boundary
/// surface            optional: receives the augmented surface with its
///                    spatial index, for the flips to go on with
///                    (flip_boundary) instead of indexing it again; it
///                    refers to `points`, which must outlive it
/// tree               optional: a tree over `points` built beforehand
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
                                  const AugmentationOptions& options = {},
                                  std::optional<BoundarySurface>* surface = nullptr,
                                  std::shared_ptr<const PointTree> tree = nullptr);

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
