// Generated test shapes with known surfaces (pmp-library's habit: tests make
// their shapes instead of loading files).
#pragma once

#include "core/triangle_mesh.h"

namespace scanstation::sim {

/// The regular icosahedron inscribed in the unit sphere, outward-oriented.
TriangleMesh icosahedron();

/// The icosahedron with each triangle split into 4 `subdivisions` times and
/// the vertices pushed to the unit sphere: 10·4^s + 2 vertices, genus 0.
TriangleMesh icosphere(int subdivisions);

/// An icosphere scaled by `radii` along x, y, z.
TriangleMesh ellipsoid(const Eigen::Vector3d& radii, int subdivisions);

/// A torus around the z axis: tube centre radius R, tube radius r, `u`
/// segments around the axis and `v` around the tube; genus 1.
TriangleMesh torus(double R, double r, int u, int v);

}  // namespace scanstation::sim
