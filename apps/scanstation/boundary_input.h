// Reading a closed boundary for the flintstone commands: a polygon (2D) or a
// closed triangle mesh (3D), told apart by the file.
#pragma once

#include "core/polygon.h"
#include "core/progress.h"
#include "core/triangle_mesh.h"

#include <filesystem>
#include <optional>
#include <string>

namespace scanstation::app {

/// Exactly one of polygon / mesh is set.
struct BoundaryInput {
  std::optional<Polygon2> polygon;
  std::optional<TriangleMesh> mesh;
};

/// svg, or points with two coordinates (in boundary order) → polygon; a mesh
/// format with faces → mesh. A 3D file without faces is rejected (InvalidInput).
BoundaryInput read_boundary(const std::filesystem::path& path, const std::optional<std::string>& format,
                            ProgressCallback progress);

}  // namespace scanstation::app
