// Summaries of data sets for `scanstation info` and for reports: counts,
// bounding box, duplicates, and mesh topology.
#pragma once

#include "core/polygon.h"
#include "core/triangle_mesh.h"

#include <nlohmann/json.hpp>

#include <vector>

namespace scanstation {

/// {"vertices", "faces", "dimension", "normals", "colors", "bounding_box":
///  {"min", "max", "diagonal"}, "duplicate_points"} and, when there are
/// faces, "topology": {closed, manifold, oriented, genus, components, ...,
/// and for an oriented manifold "simple" / "self_intersecting_pairs"}
/// plus "area", "zero_area_faces" (three distinct vertices on one line,
/// exactly) and, for a closed oriented mesh, "volume".
/// meet_properly: as for self_intersections (core/self_intersections.h),
/// faces known to meet one another properly, whose pairs are not tested.
nlohmann::json describe(const TriangleMesh& mesh, const std::vector<char>& meet_properly = {});

/// {"vertices", "perimeter", "area", "orientation": "counter-clockwise" |
///  "clockwise" | "degenerate", "simple", "bounding_box"}.
nlohmann::json describe(const Polygon2& polygon);

}  // namespace scanstation
