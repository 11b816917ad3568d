// Pictures of 2D constriction, like the thesis' Figures 5.2 and 5.3.
#pragma once

#include "reconstruct/boundary_reconstruction.h"

#include <string>

namespace scanstation {

/// An SVG with the removed Delaunay edges (dashed), the edges of the kept
/// triangulation of the interior (thin), the boundary polygon (bold) and the
/// points (red: on the boundary, black: left inside).
std::string boundary_svg(const CurveReconstruction& reconstruction);

}  // namespace scanstation
