// Wavefront OBJ: vertices and faces.
#pragma once

#include "core/progress.h"
#include "core/triangle_mesh.h"

#include <filesystem>
#include <string>
#include <string_view>

namespace scanstation::io {

/// Reads "v x y z [w] [r g b]" and "f a b c ..." records; face corners may be
/// "v", "v/vt", "v//vn" or "v/vt/vn", indices 1-based or negative (relative to
/// the vertices read so far); polygons are fan-triangulated; a trailing '\'
/// continues a line; vn, vt, g, o, s, l, usemtl, mtllib and other records
/// are skipped. Vertex colours (0..1) are kept only when every vertex has one.
/// Text with a NUL byte (a binary file) is refused. Throws FormatError naming
/// the line (the first line of a continued record).
TriangleMesh read_obj(std::string_view text, const std::filesystem::path& file, const ProgressCallback& progress = {});

/// Writes "v" and "f" records with shortest round-trip decimals (vertex
/// colours as "v x y z r g b" in 0..1 when present; vertex normals as "vn"
/// records with faces "f a//a b//b c//c" when present).
std::string write_obj(const TriangleMesh& mesh);

}  // namespace scanstation::io
