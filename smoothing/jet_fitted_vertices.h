// Vertices moved onto the surface fitted around them, a scanstation
// extension of §9.4 for scanned boundaries. The G¹ surface of Chapter 9
// interpolates the boundary's vertices, and a scan's vertices carry its
// noise: on the demo's ellipsoid (0.02 mm noise, points 1–2 mm apart) the
// interpolant's reflection lines wiggle at every vertex. Here each vertex is
// projected onto a quadratic jet fitted to its nearest vertices on the same
// side of the surface (CGAL's Monge_via_jet_fitting, as CGAL's
// jet_smooth_point_set does for point sets), where the jet stands for the
// surface. (The jet's own normal there is noisier than the plane fitted to
// the moved vertices, fitted_normals.h: a quadric's slope at one point has
// more freedom than a plane's; on the station's sphere the surface came out
// 0.020 mm RMS from the truth with the jets' normals, 0.016 with the
// planes'.) At a sharp edge or a thin
// feature a quadric does not follow the surface and would round it off; the
// fit's residual is large there against the scan's noise, and such a vertex
// stays where it was scanned.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace scanstation {

/// positions  #V by 3: moved vertices on their jets, the others as given
/// moved      the vertices moved, ascending
/// noise      the median root-mean-square residual of the jets fitted: the
///            scan's noise as the fits see it
struct JetFittedVertices {
  Eigen::MatrixX3d positions;
  std::vector<int> moved;
  double noise = 0.0;
};

/// V           #V by 3 vertex positions
/// F           #F by 3 faces, counter-clockwise from outside (closed,
///             oriented): they tell the sides of the surface
/// neighbours  how many nearest vertices (the vertex itself included) each
///             jet is fitted to: at least 10 (a quadric has six
///             coefficients), at most #V
/// A vertex is moved when it has at least 10 neighbours on its side, its
/// jet's normal turns less than 45° from its own faces' (as for the fitted
/// normals), and the jet's residual is at most 2.5 times the median
/// residual: more is a jet across a sharp edge, a thin feature or an
/// outlier's neighbourhood. A face the moves would turn over keeps its
/// corners where they were, and so do the faces around a vertex whose faces
/// fit in one hemisphere as given but would not after the moves. Throws
/// InvalidInput for a neighbour count out of range.
JetFittedVertices jet_fitted_vertices(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, int neighbours = 16);

}  // namespace scanstation
