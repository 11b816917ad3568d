#include "core/io/mesh_io.h"

#include "core/errors.h"
#include "core/io/obj.h"
#include "core/io/off.h"
#include "core/io/ply.h"
#include "core/io/stl.h"
#include "core/io/svg.h"
#include "core/io/xyz.h"

#include <cstdint>
#include <cstring>
#include <string_view>

namespace scanstation::io {

namespace fs = std::filesystem;

namespace {
// A text file saved as UTF-16 (Windows PowerShell's `>` writes it so) would
// otherwise surface as binary data or as a number that does not parse. A
// binary STL's 80-byte header is free, so it may begin with the same two
// bytes: an STL whose size matches its triangle count is left to the reader.
void reject_utf16(std::string_view bytes, const fs::path& path, FileFormat format) {
  const bool little = bytes.starts_with("\xFF\xFE"), big = bytes.starts_with("\xFE\xFF");
  if (!little && !big) return;
  if (format == FileFormat::stl && bytes.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, sizeof count);  // little endian, as STL stores it
    if (bytes.size() == 84 + 50 * std::uint64_t{count}) return;
  }
  throw FormatError(FileLocation::at_line(path, 1),
                    std::string("UTF-16 text (a ") + (little ? "little" : "big") +
                        "-endian byte-order mark): expected ASCII or UTF-8 text; convert it first, e.g. with "
                        "'iconv -f UTF-16 -t UTF-8'");
}

void require_text(FileFormat format, std::optional<Encoding> encoding) {
  if (encoding && *encoding != Encoding::ascii)
    throw InvalidInput(format_name(format) + " is a text format: it has no binary encoding");
}

TriangleMesh points_only(PointCloud cloud) {
  TriangleMesh mesh;
  mesh.vertices = std::move(cloud);
  mesh.faces.resize(0, 3);
  return mesh;
}
}  // namespace

TriangleMesh read_mesh(const fs::path& path, const ReadOptions& options) {
  const FileFormat format = resolve_format(path, options.format);
  const std::string bytes = read_file(path);
  reject_utf16(bytes, path, format);
  switch (format) {
    case FileFormat::xyz: return points_only(read_xyz(bytes, path, options.progress));
    case FileFormat::ply: return read_ply(bytes, path, options.progress);
    case FileFormat::off: return read_off(bytes, path, options.progress);
    case FileFormat::obj: return read_obj(bytes, path, options.progress);
    case FileFormat::stl: return read_stl(bytes, path, options.progress);
    case FileFormat::svg: break;
  }
  throw InvalidInput(path.string() + ": svg holds a 2D polygon, not points or a mesh (read it as a polygon)");
}

PointCloud read_points(const fs::path& path, const ReadOptions& options) {
  return read_mesh(path, options).vertices;
}

std::string encode_mesh(const TriangleMesh& mesh, FileFormat format, std::optional<Encoding> encoding) {
  switch (format) {
    case FileFormat::xyz: require_text(format, encoding); return write_xyz(mesh.vertices);
    case FileFormat::ply: return write_ply(mesh, encoding.value_or(Encoding::binary_little_endian));
    case FileFormat::off: require_text(format, encoding); return write_off(mesh);
    case FileFormat::obj: require_text(format, encoding); return write_obj(mesh);
    case FileFormat::stl:
      if (mesh.face_count() == 0) throw InvalidInput("STL stores triangles, and there are none to write");
      return write_stl(mesh, encoding.value_or(Encoding::binary_little_endian));
    case FileFormat::svg: break;
  }
  throw InvalidInput("svg holds 2D polygons: a 3D mesh or point set cannot be written as svg");
}

void write_mesh(const fs::path& path, const TriangleMesh& mesh, const WriteOptions& options) {
  const FileFormat format = resolve_format(path, options.format);
  check_writable(path, options.overwrite);
  write_file_atomically(path, encode_mesh(mesh, format, options.encoding), options.overwrite);
}

void write_points(const fs::path& path, const PointCloud& points, const WriteOptions& options) {
  write_mesh(path, points_only(points), options);
}

Polygon2 read_polygon(const fs::path& path, const ReadOptions& options) {
  const FileFormat format = resolve_format(path, options.format);
  const std::string bytes = read_file(path);
  if (format == FileFormat::svg) {
    Polygon2 polygon = read_svg(bytes, path);
    drop_closing_repeat(polygon);
    return polygon;
  }
  if (format != FileFormat::xyz)
    throw InvalidInput(path.string() + ": a polygon is read from svg or from a text list of 'x y' lines, not " +
                       format_name(format));
  reject_utf16(bytes, path, format);
  const PointCloud cloud = read_xyz(bytes, path, options.progress);
  if (cloud.dimension != 2)
    throw FormatError(FileLocation::at_line(path, 1), "expected two numbers per line ('x y') for a polygon");
  if (cloud.size() < 3)
    throw FormatError(FileLocation::whole(path),
                      "expected a polygon of at least 3 vertices, found " + std::to_string(cloud.size()));
  Polygon2 polygon;
  polygon.vertices = cloud.positions.leftCols(2);
  drop_closing_repeat(polygon);
  return polygon;
}

void write_polygon(const fs::path& path, const Polygon2& polygon, const WriteOptions& options) {
  const FileFormat format = resolve_format(path, options.format);
  check_writable(path, options.overwrite);
  std::string bytes;
  if (format == FileFormat::svg) {
    bytes = write_svg(polygon);
  } else if (format == FileFormat::xyz) {
    require_text(format, options.encoding);
    PointCloud cloud;
    cloud.positions = Eigen::MatrixX3d::Zero(polygon.size(), 3);
    cloud.positions.leftCols(2) = polygon.vertices;
    cloud.dimension = 2;
    bytes = write_xyz(cloud);
  } else {
    throw InvalidInput(path.string() + ": a polygon is written as svg or as a text list (.xy, .txt), not " +
                       format_name(format));
  }
  write_file_atomically(path, bytes, options.overwrite);
}

}  // namespace scanstation::io
