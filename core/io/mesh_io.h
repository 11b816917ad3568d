// Reading and writing points, meshes and polygons in any supported format.
#pragma once

#include "core/io/file_access.h"
#include "core/io/file_format.h"
#include "core/polygon.h"
#include "core/progress.h"
#include "core/triangle_mesh.h"

#include <filesystem>
#include <optional>
#include <string>

namespace scanstation::io {

struct ReadOptions {
  std::optional<std::string> format;  ///< overrides the extension ("ply", "xyz", ...)
  ProgressCallback progress;          ///< optional, fraction of the file parsed
};

struct WriteOptions {
  std::optional<std::string> format;  ///< overrides the extension
  /// nullopt: the format's default (binary little endian for PLY and STL,
  /// text for the others). Text-only formats reject binary encodings.
  std::optional<Encoding> encoding;
  Overwrite overwrite = Overwrite::refuse;
};

/// A mesh, or a point set as a mesh without faces, from any format but svg.
/// Throws InvalidInput / FormatError (bad input) or IoError.
TriangleMesh read_mesh(const std::filesystem::path& path, const ReadOptions& options = {});

/// The vertices of read_mesh (faces, if any, are dropped).
PointCloud read_points(const std::filesystem::path& path, const ReadOptions& options = {});

/// Writes atomically. Faces are required by STL; xyz stores only the
/// vertices (the caller decides whether dropping faces is acceptable).
void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh, const WriteOptions& options = {});
void write_points(const std::filesystem::path& path, const PointCloud& points, const WriteOptions& options = {});

/// A closed polygon from svg, or from a text point list ("x y" per line, in
/// boundary order; any 2-column xyz file).
Polygon2 read_polygon(const std::filesystem::path& path, const ReadOptions& options = {});

/// Writes a polygon as svg or as a text point list (xyz format, two columns).
void write_polygon(const std::filesystem::path& path, const Polygon2& polygon, const WriteOptions& options = {});

/// The bytes write_mesh would write, for a resolved format.
std::string encode_mesh(const TriangleMesh& mesh, FileFormat format, std::optional<Encoding> encoding);

}  // namespace scanstation::io
