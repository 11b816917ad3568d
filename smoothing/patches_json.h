// Bézier patches with their full control nets as JSON, so that other programs
// can evaluate the surface.
#pragma once

#include "smoothing/bezier_surface.h"

#include <string>

namespace scanstation {

/// {"degree": 3, "scheme": SCHEME, "control_point_order": ["b300", ..., "b003"],
///  "patches": [{"macro": f, "split": k, "control_points": [[x,y,z] ×10]}, ...]}
/// A patch is P(u,v,w) = Σ b_ijk · 3!/(i!j!k!) · u^i v^j w^k over i+j+k = 3,
/// u+v+w = 1; its corners b300, b030, b003 run counter-clockwise seen from
/// outside. k is the number of patches of macro triangle f: 6 (six-split), 3
/// (three-split) or 2 (two-split, §9.7). Numbers are the shortest decimals
/// that read back bit for bit.
/// Written as text directly (a million patches do not pass through a DOM).
std::string patches_json(const BezierSurface& surface, const std::string& scheme);

}  // namespace scanstation
