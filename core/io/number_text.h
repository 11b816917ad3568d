// Locale-independent number <-> text conversion for the text file formats.
#pragma once

#include "core/triangle_mesh.h"

#include <optional>
#include <string>
#include <string_view>

namespace scanstation::io {

/// Appends the shortest decimal form of x that reads back as exactly x
/// (std::to_chars round-trip guarantee), so an output vertex can be matched
/// to its input point by value.
void append_double(std::string& out, double x);
void append_int(std::string& out, long long x);

/// Appends the vertex and face lines that OFF and ascii PLY share:
/// "x y z[ nx ny nz][ r g b]" per vertex, then "3 a b c" per face.
void append_ascii_vertices_and_faces(std::string& out, const TriangleMesh& mesh);

/// Parses a whole token as a double ("+1.5", "-2e-3", "7"); nullopt when the
/// token is not entirely a number. NaN and infinities parse (the caller
/// decides whether they are allowed).
std::optional<double> parse_double(std::string_view token);

/// Parses a whole token as a (signed) integer; nullopt when it is not one or
/// does not fit in long long.
std::optional<long long> parse_int(std::string_view token);

}  // namespace scanstation::io
