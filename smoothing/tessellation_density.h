// How finely to tessellate a Bézier surface: the chordal deviation of a
// tessellation (smoothing/tessellation.h), and a density per patch that
// keeps it within a tolerance (as CAD exporters choose a triangulation by a
// deflection bound instead of a fixed count).
#pragma once

#include "smoothing/bezier_surface.h"
#include "smoothing/tessellation.h"

#include <nlohmann/json.hpp>
#include <optional>

namespace scanstation {

/// A power of two that brings a surface's extent near 1 (down) and its
/// inverse (up): both 1 unless the extent is beyond 2^±100, where the
/// squares of lengths overflow or underflow. Scaling by it is exact.
struct SurfaceScale {
  double down = 1.0, up = 1.0;
};
SurfaceScale surface_scale(const BezierSurface& surface);

/// The largest distance between the surface and its tessellation at
/// `density` segments per patch edge (tessellate()), both taken at the same
/// parameter: over every tessellation triangle, at its centroid and its edge
/// midpoints, the patch point against the triangle's point. The parametric
/// distance bounds the distance to the mesh from above; sampled, it is an
/// estimate of the largest one (the deviation of a cubic over a small
/// triangle peaks near those points). 0 for a surface of flat patches.
double tessellation_deviation(const BezierSurface& surface, int density);

/// A tessellation chosen for a surface.
/// plan             the density of every patch and edge
/// automatic        chosen by tolerance (else one density asked for)
/// largest_density  of any patch
/// deviation        the largest of the patches' tessellation deviations,
///                  each at its own density (on the regular grid of that
///                  density; a patch joined to finer edges has smaller
///                  triangles along them)
/// tolerance        what the automatic choice kept to (reported against a
///                  fixed density too)
/// above            patches still above the tolerance at the largest
///                  density allowed (bulges of the surface itself)
struct ChosenTessellation {
  TessellationPlan plan;
  bool automatic = true;
  int largest_density = 1;
  double deviation = 0, tolerance = 0;
  std::size_t above = 0;
};

/// Each patch at the smallest density 1..max_density whose deviation (as
/// tessellation_deviation, for that patch alone) is at most `tolerance`, or
/// at max_density; each shared edge at the larger of its two patches'
/// (plan_from_densities). CAD exporters tessellate by such a chordal bound:
/// the six-split of a dense scan is mostly flat small patches (density 1)
/// with a few bulges, and one density for all would be set by the bulges.
ChosenTessellation adaptive_tessellation(const BezierSurface& surface, double tolerance, int max_density);

/// The default tolerance for a surface: 2e-4 of the diagonal of its control
/// points' bounding box (0.02 mm on a 100 mm object): about the RMS noise
/// of the demo's scanned points (0.022% of the diagonal), a seventh of its
/// smooth surface's RMS distance to the true object. At 1e-4 the 100-step
/// chalice scan's smooth.ply has 1.8× the triangles (3.2M against 1.8M).
double default_tessellation_tolerance(const BezierSurface& surface);

/// The largest density the automatic choice gives a patch.
inline constexpr int kAutomaticDensityLimit = 16;

/// The most triangles a fixed density may ask for (about 10 GB of PLY).
inline constexpr double kMostFixedFaces = 2e8;

/// `fixed` segments per patch edge everywhere when given (its deviation
/// reported against the default tolerance), else adaptive_tessellation at
/// the default tolerance up to kAutomaticDensityLimit. Throws InvalidInput
/// when a fixed density would make more than kMostFixedFaces triangles.
ChosenTessellation choose_tessellation(const BezierSurface& surface, std::optional<int> fixed);

/// For reports: automatic, density (fixed) or largest_density, deviation,
/// tolerance, patches_above_tolerance, faces.
nlohmann::json describe(const ChosenTessellation& chosen);

}  // namespace scanstation
