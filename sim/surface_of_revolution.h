// Surfaces of revolution: turntable objects whose answer is known exactly.
#pragma once

#include "core/triangle_mesh.h"

namespace scanstation::sim {

/// profile   #P by 2 points (r, z) from the bottom pole to the top pole; the
///           first and last have r = 0 (on the z axis), the others r > 0.
///           Walking the profile upwards with the outside on the right of
///           the (r, z) plane gives outward-facing triangles.
/// segments  number of vertices around each ring (≥ 3)
/// Returns a closed genus-0 mesh: 2 poles + (#P − 2)·segments vertices.
/// Throws InvalidInput for a profile that does not start and end on the axis.
TriangleMesh surface_of_revolution(const Eigen::MatrixX2d& profile, int segments);

/// A chalice (foot, stem, bowl with an inner wall): a closed profile with a
/// deep concavity, like the thesis' chalice examples. `samples` points along
/// the profile, spaced uniformly by arc length (≥ 8).
Eigen::MatrixX2d chalice_profile(int samples);

/// A candlestick (base, grooved shaft with collars, drip pan, socket): a solid
/// of revolution with concave grooves but no cavity, like the synthetic
/// candlestick of the thesis' Figure 5.5. `samples` as for the chalice.
Eigen::MatrixX2d candlestick_profile(int samples);

/// Points of a profile resampled uniformly by arc length, ends kept.
Eigen::MatrixX2d resample_polyline(const Eigen::MatrixX2d& polyline, int samples);

}  // namespace scanstation::sim
