// Stanford PLY: ascii, binary_little_endian and binary_big_endian.
#pragma once

#include "core/io/file_format.h"
#include "core/progress.h"
#include "core/triangle_mesh.h"

#include <filesystem>
#include <string>
#include <string_view>

namespace scanstation::io {

/// Reads the "vertex" element (x, y, z; optional nx, ny, nz and red, green,
/// blue, as any scalar type) and the "face" element (list property
/// vertex_indices or vertex_index; polygons fan-triangulated). Every other
/// property and element, lists included, is skipped by its declared type, and
/// elements may come in any order. Integer colours must lie in 0..255, float
/// colours in [0, 1] (scaled to 0..255); positions, normals and colours must be
/// finite. In ascii each element entry starts on a new line and ends with a
/// line (it may wrap onto several); bytes after the last binary element are
/// ignored (some writers pad), blank text after the last ascii one too.
/// bytes     the whole file; file  its name, for error messages
/// progress  called with the fraction read, may be empty
/// Returns #V vertices (normals/colours only when all three properties exist)
/// and #F by 3 triangles.
/// Throws FormatError naming the line (header, ascii body) or byte offset
/// (binary body) and what was expected.
TriangleMesh read_ply(std::string_view bytes, const std::filesystem::path& file,
                      const ProgressCallback& progress = {});

/// Writes vertices as double x, y, z (plus double nx, ny, nz and uchar red,
/// green, blue when present) and faces as "list uchar int vertex_indices".
/// Ascii output uses shortest round-trip decimals, so values read back exactly.
/// Throws InvalidInput for what read_ply would refuse: non-finite positions or
/// normals, face indices outside [0, #V), normals/colours not #V rows.
std::string write_ply(const TriangleMesh& mesh, Encoding encoding);

}  // namespace scanstation::io
