// The file formats scanstation reads and writes, and how a path selects one.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace scanstation::io {

enum class FileFormat {
  xyz,  ///< points, one per line: "x y z [nx ny nz]" or "x y" (planar); whitespace or commas
  ply,  ///< Stanford PLY, ascii or binary (either byte order)
  off,  ///< Object File Format (OFF, COFF, NOFF, CNOFF)
  obj,  ///< Wavefront OBJ (v and f records)
  stl,  ///< STL, ascii or binary (float32, little endian)
  svg,  ///< 2D polygons (written with exact coordinates, read back from <polygon>/<path>)
};

/// How a format that has both variants is written.
enum class Encoding { ascii, binary_little_endian, binary_big_endian };

/// "xyz", "ply", ... for messages and reports.
std::string format_name(FileFormat format);

/// The format a file name's extension names (case-insensitive):
/// .xyz .xy .txt .csv .pwn -> xyz, .ply, .off, .obj, .stl, .svg.
/// nullopt for an unknown extension.
std::optional<FileFormat> format_from_extension(const std::filesystem::path& path);

/// The format chosen by `--format NAME` when given (throws InvalidInput for an
/// unknown name), else by the extension (throws InvalidInput naming the file
/// and the known extensions when there is none).
FileFormat resolve_format(const std::filesystem::path& path, const std::optional<std::string>& override_name);

/// Whether a format can store triangles (xyz and svg cannot).
bool stores_faces(FileFormat format);

}  // namespace scanstation::io
