// Unit surface normals at the vertices of a triangle mesh (thesis §9.4).
#pragma once

#include <Eigen/Core>

namespace scanstation {

/// How the incident triangles are weighted (§9.4, methods 1–3).
enum class NormalWeighting {
  area,          ///< method 1: sum of the cross products (twice the areas); the thesis' choice [Sloan, 91]
  uniform,       ///< method 2: sum of the unit face normals
  inverse_area,  ///< method 3: unit face normals divided by the face area
};

/// V #V by 3 positions, F #F by 3 counter-clockwise from outside.
/// returns #V by 3 unit normals; zero for a vertex in no face (it is not on
/// the surface, as the points constriction could not reach). Zero-area faces
/// add nothing. Throws InvalidInput naming the first vertex of some face whose
/// weighted sum vanishes (its faces have no area, or they cancel).
Eigen::MatrixX3d vertex_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                NormalWeighting weighting = NormalWeighting::area);

}  // namespace scanstation
