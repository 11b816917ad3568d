// Pictures and data files of a G¹ curve: an SVG in the style of Figure 9.1 and
// the control points as JSON.
#pragma once

#include "core/polygon.h"
#include "smoothing/g1_curve.h"

#include <nlohmann/json.hpp>
#include <string>

namespace scanstation {

/// The polygon (grey), the Bézier control polygon (dashed, with its points)
/// and the curve, y up, as one SVG document.
std::string g1_curve_svg(const Polygon2& polygon, const G1Curve& curve);

/// {"degree": 3, "closed": true, "segments": [{"control_points": [[x,y] ×4]}, ...],
///  "repaired_vertices": [...], "unrepaired_vertices": [...]}; segment i runs
/// from vertex i to vertex i+1 as P(t) = Σ p_j · C(3,j) t^j (1−t)^(3−j).
nlohmann::json g1_curve_json(const G1Curve& curve);

}  // namespace scanstation
