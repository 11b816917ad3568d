#include "boundary_input.h"

#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/log.h"
#include "core/polygon.h"

namespace scanstation::app {

namespace {

// A crossing or overlapping outline (a bow tie, points along one line) is
// read, but not without a word: the flintstones, inclusion and smoothing
// of Chapters 7 and 9 are those of a simple polygon's region.
void warn_unless_simple(const BoundaryInput& input) {
  if (input.polygon->size() >= 3 && !is_simple(*input.polygon))
    room_logger("scanstation")
        ->warn("{}: the polygon is not simple (edges cross, overlap or meet beyond their shared corners): what is "
               "computed assumes a simple one, so the result has no meaning there",
               input.path.string());
}

}  // namespace

BoundaryInput read_boundary(const std::filesystem::path& path, const std::optional<std::string>& format,
                            ProgressCallback progress) {
  BoundaryInput input;
  input.path = path;
  if (io::resolve_format(path, format) == io::FileFormat::svg) {
    input.polygon = io::read_polygon(path, {format, progress});
    warn_unless_simple(input);
    return input;
  }
  TriangleMesh mesh = io::read_mesh(path, {format, progress});
  if (mesh.vertices.dimension == 2 && mesh.face_count() == 0) {
    input.polygon = Polygon2{mesh.vertices.positions.leftCols(2)};
    drop_closing_repeat(*input.polygon);
    warn_unless_simple(input);
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
