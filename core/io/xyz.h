// Point lists as text: XYZ, CSV, PWN.
#pragma once

#include "core/point_cloud.h"
#include "core/progress.h"

#include <filesystem>
#include <string>
#include <string_view>

namespace scanstation::io {

/// Reads one point per line, separated by whitespace and/or commas:
/// "x y" (planar, dimension 2), "x y z", or "x y z nx ny nz". Every line must
/// have the same number of columns; '#' starts a comment; one header line of
/// column names (as CSV files often have) is skipped. Throws FormatError
/// naming the line.
PointCloud read_xyz(std::string_view text, const std::filesystem::path& file, const ProgressCallback& progress = {});

/// Writes "x y" (dimension 2), "x y z" or "x y z nx ny nz" lines with
/// shortest round-trip decimals, separated by `separator` (' ' or ',').
std::string write_xyz(const PointCloud& points, char separator = ' ');

}  // namespace scanstation::io
