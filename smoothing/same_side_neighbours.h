// The nearest vertices of a mesh vertex that lie on the same side of the
// surface: the neighbourhood the station's fitted normals and fitted
// positions (fitted_normals.h, jet_fitted_vertices.h) are computed from.
// Across a thin wall (a cup's rim, a plate) the nearest points may lie on the
// other face, whose normals point the other way; those are left out.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <vector>

namespace scanstation {

class SameSideNeighbours {
 public:
  /// V  #V by 3 vertex positions; F  #F by 3 faces, counter-clockwise from
  /// outside. Builds a k-d tree over the vertices (CGAL) and the
  /// area-weighted face normals of §9.4 (method 1) that tell the sides.
  SameSideNeighbours(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);
  ~SameSideNeighbours();

  /// The area-weighted face normal at each vertex (zero off the surface).
  const Eigen::MatrixX3d& side() const { return side_; }

  /// Of the `k` nearest vertices of v (v itself first, then by distance),
  /// those whose side is less than 90° from v's, into `out`; empty for a
  /// vertex in no face.
  void near(Eigen::Index v, int k, std::vector<Eigen::Index>& out) const;

 private:
  struct Tree;
  Eigen::MatrixX3d side_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace scanstation
