// Lines of sight through a Delaunay tetrahedralization: a scanned point was
// seen from the camera, so the segment between them runs through empty space
// and every tetrahedron it crosses lies outside the object. Constriction
// removes those first (ConstrictionOptions::carve_first), which carves the
// concavities a turntable scan sees — waists, stems — instead of reaching
// their points through slits (a scanstation extension of Chapter 5).
#pragma once

#include "reconstruct/delaunay_complex.h"

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace scanstation {

/// One line of sight: the point with index `point` (a vertex of the complex)
/// was seen from `viewpoint`.
struct SightLine {
  int point;
  Eigen::Vector3d viewpoint;
};

/// dt      a 3D Delaunay complex; points  its vertices' positions (#P by 3;
///         dt.points or any copy scaled by a power of two: only signs of
///         exact orientation tests are used)
/// lines   sight lines, viewpoints in the same coordinates
/// returns per cell of dt, −1 when no segment from a point towards its
///         viewpoint passes through the cell's interior, else its depth: the
///         fewest cells between it and the end of such a segment (the
///         viewpoint, or where the segment leaves the convex hull), 0 for
///         the last cell crossed. Walked cell to cell from the point with
///         exact orientation tests (a segment grazing an edge or a vertex
///         continues into one of the cells there). Lines with a non-finite
///         viewpoint or a point in no cell are skipped.
/// whole_stars  the points [0, whole_stars) have every finite cell around
///         them in dt (all of them for a whole triangulation; a part of one
///         may hold the rest): a face through such a point with no
///         neighbour is a convex hull face, and a viewpoint beyond it is
///         seen from outside the hull at once, without searching the star.
std::vector<int> line_of_sight_depths(const DelaunayComplex<3>& dt, const Eigen::MatrixX3d& points,
                                      const std::vector<SightLine>& lines,
                                      Eigen::Index whole_stars = std::numeric_limits<Eigen::Index>::max());

}  // namespace scanstation
