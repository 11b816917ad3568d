// A triangle mesh of a Bézier surface at a chosen density, with the exact
// surface normals at its vertices.
#pragma once

#include "core/io/file_access.h"
#include "core/triangle_mesh.h"
#include "smoothing/bezier_surface.h"

#include <filesystem>

namespace scanstation {

/// density  n ≥ 1 segments per patch edge: (n+1)(n+2)/2 points and n²
/// triangles per patch. Points on a shared patch edge are computed from that
/// edge's four control points in one canonical direction, so both patches
/// produce them bit for bit and they are welded: a closed surface gives a
/// closed (watertight) mesh. Normals are the unit patch normals (Eq. 8.4).
TriangleMesh tessellate(const BezierSurface& surface, int density);

/// The same mesh streamed to a binary little-endian PLY (double x y z nx ny
/// nz, int faces) without holding it in memory: vertex numbers come from the
/// patch topology (patch corners, then the inner points of every patch edge,
/// then each patch's inner points), so only the corners are hashed. Written
/// atomically; the same closed, oriented connectivity as tessellate().
void write_tessellation_ply(const BezierSurface& surface, int density, const std::filesystem::path& path,
                            io::Overwrite overwrite);

}  // namespace scanstation
