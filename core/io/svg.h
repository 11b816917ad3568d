// Closed polygons as SVG.
#pragma once

#include "core/polygon.h"

#include <filesystem>
#include <string>
#include <string_view>

namespace scanstation::io {

/// Reads the first <polygon points="..."> (or <polyline>, or <path d="...">
/// with M/L/H/V/Z commands, absolute or relative) of an SVG file, in
/// document order; the file is parsed as XML (pugixml), and one that is not
/// well-formed is refused at the line of the fault. Points are
/// read as written, so a file written by write_svg reads back exactly;
/// transforms are not applied, and other shape elements are not read: both
/// are named in a warning (the "core" logger). Throws FormatError naming the
/// line.
Polygon2 read_svg(std::string_view text, const std::filesystem::path& file);

/// Draws the polygon (outline and vertex dots) with the y axis pointing up;
/// the coordinates inside are the exact input values (shortest round-trip),
/// the flip is a transform.
std::string write_svg(const Polygon2& polygon);

}  // namespace scanstation::io
