// Legacy VTK unstructured grids: the interior triangulations (§5.8) as
// triangles or tetrahedra, readable by ParaView and VTK-based tools.
#pragma once

#include <Eigen/Core>
#include <string>

namespace scanstation::io {

/// points  #P by 3 positions
/// cells   #C by 3 (triangles, VTK_TRIANGLE) or #C by 4 (tetrahedra,
///         VTK_TETRA) indices into points
/// Returns an ascii "# vtk DataFile Version 3.0" document with shortest
/// round-trip coordinates.
std::string write_vtk_cells(const Eigen::MatrixX3d& points, const Eigen::MatrixXi& cells);

}  // namespace scanstation::io
