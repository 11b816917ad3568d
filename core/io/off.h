// Object File Format: OFF, COFF, NOFF, CNOFF (ascii).
#pragma once

#include "core/progress.h"
#include "core/triangle_mesh.h"

#include <filesystem>
#include <string>
#include <string_view>

namespace scanstation::io {

/// Reads the header keyword ([C][N]OFF, counts "nv nf [ne]" on the same or the
/// next line), the vertices "x y z [nx ny nz] [r g b [a]]" (normals for N,
/// colours for C as 0..255 integers or 0..1 floats; a plain OFF vertex line
/// with more than 3 numbers is an error) and the faces "n i0 ... in-1 [colour]"
/// (0-based; polygons fan-triangulated (0,k,k+1); face colours ignored).
/// '#' starts a comment anywhere on a line; anything but comments after the
/// last face is an error. Throws FormatError naming the line.
TriangleMesh read_off(std::string_view text, const std::filesystem::path& file, const ProgressCallback& progress = {});

/// Writes OFF (NOFF/COFF/CNOFF when normals/colours are present) with
/// shortest round-trip decimals.
std::string write_off(const TriangleMesh& mesh);

}  // namespace scanstation::io
