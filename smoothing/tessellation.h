// A triangle mesh of a Bézier surface at a chosen density, with the exact
// surface normals at its vertices.
#pragma once

#include "core/triangle_mesh.h"
#include "smoothing/bezier_surface.h"

namespace scanstation {

/// density  n ≥ 1 segments per patch edge: (n+1)(n+2)/2 points and n²
/// triangles per patch. Points on a shared patch edge are computed from that
/// edge's four control points in one canonical direction, so both patches
/// produce them bit for bit and they are welded: a closed surface gives a
/// closed (watertight) mesh. Normals are the unit patch normals (Eq. 8.4).
TriangleMesh tessellate(const BezierSurface& surface, int density);

}  // namespace scanstation
