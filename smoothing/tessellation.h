// A triangle mesh of a Bézier surface, at one density or at a density per
// patch (smoothing/tessellation_density.h), with the exact surface normals
// at its vertices.
#pragma once

#include "core/io/file_access.h"
#include "core/triangle_mesh.h"
#include "smoothing/bezier_surface.h"
#include "smoothing/patch_adjacency.h"

#include <filesystem>
#include <vector>

namespace scanstation {

/// How finely each patch is tessellated: inner[p] segments per edge of patch
/// p's own grid, edge[3p + k] segments along its edge k (from corner k to
/// k+1), the same on both patches of a shared edge and at least inner[p].
/// A patch whose three edges have inner[p] segments is the regular grid:
/// (n+1)(n+2)/2 points and n² triangles. Another keeps the grid of density
/// m = max(inner[p], 3) inside its border ring and joins each edge's points
/// to that grid's border row by a band of triangles, zipped in order along
/// the edge (m = 3: a fan around the grid's one inner point).
struct TessellationPlan {
  std::vector<int> inner, edge;
  /// The shared patch edges (patch_adjacency) when the plan was made with
  /// them (plan_from_densities), so that writing the plan does not look
  /// for them again; empty: found when needed.
  std::vector<PatchEdgePair> shared;
  std::size_t face_count() const;
};

/// Every patch and edge at `density` segments (≥ 1).
TessellationPlan uniform_plan(const BezierSurface& surface, int density);

/// Patch p at density[p] (≥ 1); a shared edge takes the larger of its two
/// patches' densities, so a finer patch never leaves a crack beside a
/// coarser one.
TessellationPlan plan_from_densities(const BezierSurface& surface, std::vector<int> density);

/// The triangle mesh of the plan. Points on a shared patch edge are
/// computed from that edge's four control points in one canonical
/// direction, so both patches produce them bit for bit and they are welded:
/// a closed surface gives a closed (watertight) mesh. Normals are the unit
/// patch normals (Eq. 8.4).
TriangleMesh tessellate(const BezierSurface& surface, const TessellationPlan& plan);

/// The uniform plan at density n ≥ 1.
TriangleMesh tessellate(const BezierSurface& surface, int density);

/// The same mesh streamed to a binary little-endian PLY (double x y z nx ny
/// nz, int faces) without holding it in memory: vertex numbers come from the
/// patch topology (patch corners, then the inner points of every patch edge,
/// then each patch's inner points), so only the corners are hashed. Written
/// atomically; the same closed, oriented connectivity as tessellate().
void write_tessellation_ply(const BezierSurface& surface, const TessellationPlan& plan,
                            const std::filesystem::path& path, io::Overwrite overwrite);
void write_tessellation_ply(const BezierSurface& surface, int density, const std::filesystem::path& path,
                            io::Overwrite overwrite);

}  // namespace scanstation
