// Reading a closed boundary for the flintstone commands: a polygon (2D) or a
// closed triangle mesh (3D), told apart by the file.
#pragma once

#include "core/polygon.h"
#include "core/progress.h"
#include "core/triangle_mesh.h"
#include "reconstruct/flintstone_tree2.h"
#include "reconstruct/flintstone_tree3.h"

#include <filesystem>
#include <optional>
#include <string>

namespace scanstation::app {

/// Exactly one of polygon / mesh is set.
struct BoundaryInput {
  std::filesystem::path path;
  std::optional<Polygon2> polygon;
  std::optional<TriangleMesh> mesh;
};

/// svg, or points with two coordinates (in boundary order) → polygon; a mesh
/// format with faces → mesh. A 3D file without faces is rejected (InvalidInput).
BoundaryInput read_boundary(const std::filesystem::path& path, const std::optional<std::string>& format,
                            ProgressCallback progress);

/// The flintstone tree of the input's polygon / mesh. A boundary the tree
/// cannot take (too few vertices, not closed, not manifold) is bad input:
/// InvalidInput naming the file.
FlintstoneTree2 polygon_tree(const BoundaryInput& input);
FlintstoneTree3 mesh_tree(const BoundaryInput& input, const FlintstoneOptions3& options = {});

}  // namespace scanstation::app
