#include "boundary_input.h"

#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace scanstation::app {

BoundaryInput read_boundary(const std::filesystem::path& path, const std::optional<std::string>& format,
                            ProgressCallback progress) {
  BoundaryInput input;
  if (io::resolve_format(path, format) == io::FileFormat::svg) {
    input.polygon = io::read_polygon(path, {format, progress});
    return input;
  }
  TriangleMesh mesh = io::read_mesh(path, {format, progress});
  if (mesh.vertices.dimension == 2 && mesh.face_count() == 0) {
    input.polygon = Polygon2{mesh.vertices.positions.leftCols(2)};
  } else if (mesh.face_count() > 0) {
    input.mesh = std::move(mesh);
  } else {
    throw InvalidInput(path.string() + ": 3D points without faces have no boundary; give a closed triangle mesh "
                       "(or 2D points in boundary order for a polygon)");
  }
  return input;
}

}  // namespace scanstation::app
