// Closed 2D outlines with known answers, like the thesis' 2D examples: the
// chalice silhouette (Figures 1.1, 5.2) and a face profile (Figure 5.3).
#pragma once

#include "core/polygon.h"

namespace scanstation::sim {

/// The chalice's profile mirrored about its axis: a closed counter-clockwise
/// silhouette with a deep concave bowl. About `samples` vertices, spaced
/// uniformly by arc length (≥ 8).
Polygon2 chalice_outline(int samples);

/// A human head seen from the side (forehead, brow, nose, lips, chin, neck,
/// back of the head): a closed counter-clockwise outline with the small
/// concavities of the thesis' face profile. `samples` vertices (≥ 16),
/// uniformly spaced by arc length along a smoothed key polygon.
Polygon2 face_profile_outline(int samples);

/// The closed polygon resampled with `samples` vertices spaced uniformly by
/// arc length, starting at vertex 0.
Polygon2 resample_closed(const Polygon2& polygon, int samples);

}  // namespace scanstation::sim
