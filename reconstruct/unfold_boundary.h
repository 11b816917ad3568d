// Folds of a closed boundary re-triangulated over a plane.
//
// Where the points are nearly coplanar and sparse (the flat top of a scanned
// object, a strip the sensor did not see, a gap bridged by long triangles),
// the Delaunay cells are slivers and constriction (Chapter 5) may leave the
// boundary doubled over itself: two faces across an edge whose normals point
// almost opposite ways, the surface folding back within a hair of a plane.
// The boundary is still closed, simple and through every point, but its
// normals there are meaningless: shading shows creases, and at a fold no
// vertex normal meets the sign condition of G¹ smoothing (§9.6, §9.8).
#pragma once

#include <Eigen/Core>

#include <cstddef>

namespace scanstation {

class BoundarySurface;

struct UnfoldStatistics {
  std::size_t folds_before = 0;    ///< fold edges found
  std::size_t folds_after = 0;     ///< fold edges left
  std::size_t patches = 0;         ///< connected fold regions looked at
  std::size_t retriangulated = 0;  ///< of them, replaced by a flat triangulation
};

/// Re-triangulates the folds of a closed, oriented, 2-manifold boundary.
/// A fold is an edge whose two faces' normals differ by more than
/// fold_degrees. Around each connected group of folds, the faces at their
/// vertices form a patch; if the patch is a disk whose boundary loop
/// projects to a simple polygon on the plane of its vector area, with every
/// inner vertex strictly inside, the patch is replaced by the constrained
/// Delaunay triangulation of that polygon and its inner vertices (CGAL),
/// lifted back to the same points. The replacement is kept only if it has
/// fewer folds (its own edges and the loop's) and passes the exact tests:
/// no triangle flat, no edge doubled with the rest of the surface, no
/// triangle meeting another anywhere but in shared vertices and edges. A
/// patch that fails is grown by a ring of faces and tried again (twice).
/// So the result stays closed, 2-manifold, simple, of the same genus, and
/// through the same points.
/// P #P by 3 positions; F #F by 3 faces, counter-clockwise seen from
/// outside, replaced by the result (same count: a disk is replaced by a
/// disk on the same vertices); keep #K by 3 faces that must stay (§5.7): a
/// patch holding one is left as it is.
UnfoldStatistics unfold_boundary(const Eigen::MatrixX3d& P, Eigen::MatrixX3i& F,
                                 const Eigen::MatrixXi& keep = Eigen::MatrixXi(0, 3), double fold_degrees = 120.0);

/// The same with the spatial index of F over P already built (the flips',
/// see flip_boundary), which is changed along with F.
UnfoldStatistics unfold_boundary(BoundarySurface& surface, const Eigen::MatrixX3d& P, Eigen::MatrixX3i& F,
                                 const Eigen::MatrixXi& keep = Eigen::MatrixXi(0, 3), double fold_degrees = 120.0);

}  // namespace scanstation
