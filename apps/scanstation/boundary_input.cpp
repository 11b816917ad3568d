#include "boundary_input.h"

#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace scanstation::app {

BoundaryInput read_boundary(const std::filesystem::path& path, const std::optional<std::string>& format,
                            ProgressCallback progress) {
  BoundaryInput input;
  input.path = path;
  if (io::resolve_format(path, format) == io::FileFormat::svg) {
    input.polygon = io::read_polygon(path, {format, progress});
    return input;
  }
  TriangleMesh mesh = io::read_mesh(path, {format, progress});
  if (mesh.vertices.dimension == 2 && mesh.face_count() == 0) {
    input.polygon = Polygon2{mesh.vertices.positions.leftCols(2)};
    drop_closing_repeat(*input.polygon);
  } else if (mesh.face_count() > 0) {
    input.mesh = std::move(mesh);
  } else {
    throw InvalidInput(path.string() + ": 3D points without faces have no boundary; give a closed triangle mesh "
                       "(or 2D points in boundary order for a polygon)");
  }
  return input;
}

namespace {
template <typename Build>
auto naming_file(const std::filesystem::path& path, const Build& build) {
  try {
    return build();
  } catch (const TopologyError& e) {
    throw InvalidInput(path.string() + ": " + e.what());
  } catch (const InvalidInput& e) {
    throw InvalidInput(path.string() + ": " + e.what());
  }
}
}  // namespace

FlintstoneTree2 polygon_tree(const BoundaryInput& input) {
  return naming_file(input.path, [&] { return flintstone_tree(*input.polygon); });
}

FlintstoneTree3 mesh_tree(const BoundaryInput& input, const FlintstoneOptions3& options) {
  return naming_file(input.path, [&] { return flintstone_tree(*input.mesh, options); });
}

}  // namespace scanstation::app
