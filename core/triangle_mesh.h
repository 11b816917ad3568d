// Indexed triangle mesh: shared vertices plus triangles referencing them.
#pragma once

#include "core/point_cloud.h"

namespace scanstation {

/// vertices  the #V vertices (positions, optional normals/colours)
/// faces     #F by 3 vertex indices into vertices, counter-clockwise seen from
///           outside for a consistently oriented closed mesh; #F may be 0
///           (a point set read from a mesh format)
struct TriangleMesh {
  PointCloud vertices;
  Eigen::MatrixX3i faces;

  Eigen::Index vertex_count() const { return vertices.size(); }
  Eigen::Index face_count() const { return faces.rows(); }
};

}  // namespace scanstation
