// Edge flips on a finished boundary: the vertex set, closedness, genus and
// simplicity stay; only which triangles join the points changes.
#pragma once

#include "reconstruct/delaunay_complex.h"

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

namespace scanstation {

class BoundarySurface;
class PointTree;

/// What a flip should lower.
enum class FlipCriterion {
  area,  ///< the area of the two triangles: O'Rourke's minimal-area flips (thesis §4.3.2)
  /// area flips, then Delaunay flips where the surface is nearly flat: an
  /// edge whose two opposite angles sum beyond π, between faces whose
  /// normals are within 45°, becomes the other diagonal when that one is
  /// locally Delaunay (real meshes are: 82–100% of the edges of CGAL's 26
  /// closed genus-0 meshes)
  area_then_delaunay,
};

/// points    #P by 3 positions
/// boundary  (in/out) #F by 3 closed, simple, genus-0 surface, counter-clockwise
///           from outside
/// keep      #K by 3 triangles never flipped away (§5.7), may be empty
/// min_gain  the relative drop a flip must bring: on a smooth convex patch a
///           flip into a shallow dent lowers the area by a hair, and such
///           dents are not the surface; 1e-3 keeps random samples of an
///           ellipsoid untouched while caps over concavities still go
/// cells     optional: the Delaunay cells over `points` from which `boundary`
///           was constricted (and perhaps augmented: its triangles that are
///           no faces of them are found and kept away from; with `surface`
///           given, that surface was built from the cells' boundary, and the
///           triangles of its later edits are the foreign ones)
/// An edge (a, b) between (a, b, c) and (b, a, d) becomes (c, d) when that
/// lowers the criterion (area: by min_gain), (c, d) is not already an edge, the tetrahedron
/// (a, b, c, d) holds no other point, and the new triangles meet the surface
/// only in shared vertices and edges (exact tests). With `cells`, a flip whose
/// tetrahedron is one of them is tested only against the triangles that are
/// no cell faces (augmentation's, and those of earlier flips whose
/// tetrahedron was no cell): its new triangles are faces of the Delaunay
/// complex, which meet the other cell faces properly, and a Delaunay cell is
/// not flat and holds no point (the same flips as with every flip tested,
/// faster: docs/design.md).
/// surface  optional: the spatial index of `boundary` over `points`, when an
///          earlier step (augmentation) built one, flipped in place instead
///          of a new one; when empty, it receives the index the flips built
///          (if there were candidates), for a later step on the same surface
///          (unfold_boundary) to go on with
/// around   optional, with `cells`: the cells around each of their points,
///          shared with the steps before (built here when empty)
/// tree     optional: a tree over `points` for the surface built here
/// Returns the flips made.
std::size_t flip_boundary(const Eigen::MatrixX3d& points, Eigen::MatrixX3i& boundary, FlipCriterion criterion,
                          const Eigen::MatrixXi& keep, double min_gain = 1e-3,
                          const DelaunayComplex<3>* cells = nullptr,
                          std::optional<BoundarySurface>* surface = nullptr,
                          std::optional<CellsAround>* around = nullptr,
                          std::shared_ptr<const PointTree> tree = nullptr);

/// Delaunay flips of the boundary of a union of Delaunay cells, each made by
/// adding or removing one cell: an edge (a, b) between the boundary
/// triangles (a, b, c) and (b, a, d) becomes (c, d) when (a, b, c, d) is a
/// cell with exactly those two faces on the boundary, (c, d) is not on the
/// boundary yet, and FlipCriterion::area_then_delaunay's Delaunay flip
/// wants it (the angles opposite (a, b) sum beyond π, the quad is flat
/// within 45°, and (c, d) is locally Delaunay); in one sweep over the cells
/// in storage order (Lawson's order), each flip's surroundings examined at
/// once, until no edge is left to flip or 8 flips per point were made.
/// A cell's faces meet the other cell
/// faces only in shared vertices and edges, so no flip needs a geometric
/// test, and the boundary stays closed, 2-manifold and of the same genus
/// through the same points (a flip of a cell union is constriction's
/// two-face removal, §5.3, or its inverse); `kept` stays a triangulation of
/// the enclosed solid (§5.8).
/// complex  the Delaunay complex
/// kept     (in/out) one flag per cell, 1 inside: its boundary must be a
///          closed 2-manifold
/// keep     #K by 3 triangles never flipped away (§5.7), may be empty
/// Returns the flips made.
std::size_t flip_delaunay_cells(const DelaunayComplex<3>& complex, std::vector<char>& kept, const Eigen::MatrixXi& keep);

}  // namespace scanstation
