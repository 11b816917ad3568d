// Pictures of 2D flintstone approximations, like the thesis' Figures 7.4 and 7.6.
#pragma once

#include "reconstruct/flintstone_approximation.h"

#include <string>

namespace scanstation {

/// An SVG with the flintstones of the approximation's edges (light fill), the
/// original polygon (grey), the approximation (bold) and its vertices.
std::string flintstone_svg(const FlintstoneTree2& tree, const PolygonApproximation& approximation);

/// The boundary of a flintstone as a polygon: the lens of two discs (or the
/// outline of both discs for a union), `samples` points per circle.
Eigen::MatrixX2d flintstone_outline(const Flintstone<2>& stone, int samples = 96);

}  // namespace scanstation
