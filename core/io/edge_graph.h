// Points and the edges between them (a geometric graph in space) as OBJ line
// records or an ascii PLY with an "edge" element — the two mesh formats that
// viewers (MeshLab, ParaView, Blender) read edges from.
#pragma once

#include <Eigen/Core>

#include <string>

namespace scanstation::io {

/// V  #V by 3 positions; E  #E by 2 vertex indices (0-based) into V.
/// OBJ: "v x y z" per point, "l a b" per edge (1-based).
std::string write_edges_obj(const Eigen::MatrixX3d& V, const Eigen::MatrixX2i& E);

/// PLY (ascii 1.0): element vertex (x, y, z as double), element edge
/// (vertex1, vertex2 as int), the PLY specification's edge element.
std::string write_edges_ply(const Eigen::MatrixX3d& V, const Eigen::MatrixX2i& E);

}  // namespace scanstation::io
