// STL: ascii and binary.
#pragma once

#include "core/io/file_format.h"
#include "core/progress.h"
#include "core/triangle_mesh.h"

#include <filesystem>
#include <string>
#include <string_view>

namespace scanstation::io {

/// Reads ascii ("solid ... facet normal ... outer loop vertex ... endloop
/// endfacet ... endsolid") or binary STL (80-byte header, uint32 count,
/// 50 bytes per triangle); a binary file is recognised by its size
/// (84 + 50 n bytes) even when its header starts with "solid". Ascii keywords
/// are read without case, facet normals are ignored, and several solids may
/// follow each other. Corners with identical coordinates become one shared
/// vertex (-0 and +0 alike, stored as +0), numbered in order of first
/// appearance, so the mesh is indexed. Throws FormatError naming the line or
/// byte offset.
TriangleMesh read_stl(std::string_view bytes, const std::filesystem::path& file, const ProgressCallback& progress = {});

/// Writes binary STL (little endian float32, as the format requires: values
/// are rounded to float) or ascii STL (shortest round-trip decimals) with
/// facet normals computed from the triangles (zero for degenerate ones). The
/// binary header never starts with "solid". Big-endian is not an STL variant,
/// and binary cannot hold coordinates beyond float range: both are rejected
/// with InvalidInput.
std::string write_stl(const TriangleMesh& mesh, Encoding encoding);

}  // namespace scanstation::io
