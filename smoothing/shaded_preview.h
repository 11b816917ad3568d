// A shaded picture of a scan's result, to look at rather than read: the
// constricted boundary (flat triangles) beside the smooth surface, from the
// front and from behind.
#pragma once

#include "core/triangle_mesh.h"

#include <Eigen/Core>
#include <string>

namespace scanstation {

/// panel_px  size of each square panel; up  the object's up direction (the
/// turntable axis for a scan).
struct PreviewOptions {
  int panel_px = 400;
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
};

/// PNG bytes of a 2 × 2 grid: columns `boundary` (face normals, clay) and
/// `smooth` (its vertex normals interpolated, blue-grey; empty → the
/// boundary again, smooth-shaded if it has normals), rows seen obliquely
/// from the front and from the opposite side, all in one scale. Two lights
/// and an ambient term (Lambert); flat faces seen from inside are dark red,
/// so a wrongly oriented triangle shows. Throws InvalidInput when `boundary` has no faces.
std::string shaded_preview_png(const TriangleMesh& boundary, const TriangleMesh& smooth,
                               const PreviewOptions& options = {});

}  // namespace scanstation
