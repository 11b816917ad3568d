#include "core/io/stl.h"

#include "core/io/byte_cursor.h"
#include "core/io/number_text.h"
#include "core/io/text_lines.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace scanstation::io {

namespace {

constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kCountBytes = 4;
constexpr std::size_t kTriangleBytes = 50;  // normal, 3 corners (12 float32), uint16 attribute
constexpr std::uint32_t kProgressStride = 1 << 16;

// STL stores every corner of every triangle; identical coordinates are one
// vertex. An open-addressing table of vertex ids keyed by the coordinate bits
// keeps the merge linear and allocation-free per corner.
class CornerMerger {
 public:
  explicit CornerMerger(std::size_t expected_vertices) {
    std::size_t capacity = 64;
    while (capacity < 2 * expected_vertices) capacity *= 2;
    slots_.assign(capacity, -1);
  }

  int vertex(double x, double y, double z) {
    // -0.0 == 0.0 is the same point; only the bits would differ.
    const double p[3] = {x == 0.0 ? 0.0 : x, y == 0.0 ? 0.0 : y, z == 0.0 ? 0.0 : z};
    if (2 * (count() + 1) > slots_.size()) grow();
    std::size_t slot = hash(p) & (slots_.size() - 1);
    for (; slots_[slot] >= 0; slot = (slot + 1) & (slots_.size() - 1))
      if (std::equal(p, p + 3, positions_.begin() + 3 * slots_[slot])) return slots_[slot];
    slots_[slot] = static_cast<int>(count());
    positions_.insert(positions_.end(), p, p + 3);
    return slots_[slot];
  }

  std::size_t count() const { return positions_.size() / 3; }
  const std::vector<double>& positions() const { return positions_; }

 private:
  static std::size_t hash(const double* p) {
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (int a = 0; a < 3; ++a) {
      h ^= std::bit_cast<std::uint64_t>(p[a]) + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
      h *= 0xBF58476D1CE4E5B9ull;
      h ^= h >> 31;
    }
    return static_cast<std::size_t>(h);
  }

  void grow() {
    std::vector<int> old(2 * slots_.size(), -1);
    old.swap(slots_);
    for (std::size_t v = 0; v < count(); ++v) {
      std::size_t slot = hash(&positions_[3 * v]) & (slots_.size() - 1);
      while (slots_[slot] >= 0) slot = (slot + 1) & (slots_.size() - 1);
      slots_[slot] = static_cast<int>(v);
    }
  }

  std::vector<int> slots_;
  std::vector<double> positions_;
};

TriangleMesh indexed_mesh(const CornerMerger& merger, const std::vector<int>& triangles) {
  using RowMajorD = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  using RowMajorI = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
  TriangleMesh mesh;
  mesh.vertices.positions = Eigen::Map<const RowMajorD>(merger.positions().data(),
                                                        static_cast<Eigen::Index>(merger.count()), 3);
  mesh.faces = Eigen::Map<const RowMajorI>(triangles.data(), static_cast<Eigen::Index>(triangles.size() / 3), 3);
  return mesh;
}

const char* const kAxes[3] = {"x", "y", "z"};

// ---- binary --------------------------------------------------------------

TriangleMesh read_binary(std::string_view bytes, const std::filesystem::path& file, std::uint32_t count,
                         const ProgressCallback& progress) {
  ByteCursor cursor(bytes, file, kHeaderBytes + kCountBytes);
  CornerMerger merger(count / 2);  // a closed triangle mesh has about half as many vertices as triangles
  std::vector<int> triangles;
  triangles.reserve(3 * std::size_t{count});
  for (std::uint32_t t = 0; t < count; ++t) {
    cursor.skip(12, "the facet normal");  // recomputed by whoever needs it; often zero or stale
    for (int corner = 0; corner < 3; ++corner) {
      float p[3];
      for (int a = 0; a < 3; ++a) {
        const std::size_t at = cursor.offset();
        p[a] = cursor.read<float>(std::endian::little, "a vertex coordinate");
        if (!std::isfinite(p[a]))
          throw FormatError(FileLocation::at_byte(file, at),
                            std::string("expected a finite ") + kAxes[a] + " coordinate of corner " +
                                std::to_string(corner) + " of triangle " + std::to_string(t) + ", found " +
                                std::to_string(p[a]));
      }
      triangles.push_back(merger.vertex(p[0], p[1], p[2]));
    }
    cursor.skip(2, "the attribute byte count");
    if (progress && (t + 1) % kProgressStride == 0) progress(static_cast<double>(t + 1) / count);
  }
  if (progress) progress(1.0);
  return indexed_mesh(merger, triangles);
}

// ---- ascii ---------------------------------------------------------------

// Keywords compared without case: some CAD exporters write "SOLID", "FACET".
bool is_keyword(std::string_view token, std::string_view keyword) {
  return std::equal(token.begin(), token.end(), keyword.begin(), keyword.end(),
                    [](char a, char b) { return (a >= 'A' && a <= 'Z' ? a - 'A' + 'a' : a) == b; });
}

// The tokens of the current line. Errors go through TextLines::fail: a
// LineTokens with its own location would copy the file path for every line,
// which costs more than parsing the line.
LineTokens fields(const TextLines& lines) { return LineTokens(lines.line(), FileLocation{}); }

bool starts_with_solid(std::string_view bytes) {
  const std::size_t first = std::min(bytes.find_first_not_of(" \t\r\n"), bytes.size());
  return is_keyword(bytes.substr(first, 5), "solid");
}

// Moves to the next line and checks that it starts with `keyword`; returns the
// rest of the line.
LineTokens expect_line(TextLines& lines, std::string_view keyword, std::string_view expected) {
  lines.require_next(expected);
  LineTokens tokens = fields(lines);
  const std::string_view word = tokens.next();
  if (!is_keyword(word, keyword)) lines.fail("expected " + std::string(expected) + ", found " + quoted(word));
  return tokens;
}

void read_ascii_vertex(const TextLines& lines, LineTokens& tokens, std::size_t facet, std::size_t corner,
                       double (&p)[3]) {
  for (int a = 0; a < 3; ++a) {
    const std::string_view token = tokens.next();
    const auto value = parse_double(token);
    if (value && std::isfinite(*value)) {
      p[a] = *value;
      continue;
    }
    const std::string what = std::string("the ") + kAxes[a] + " coordinate of corner " + std::to_string(corner) +
                             " of facet " + std::to_string(facet);
    if (token.empty()) lines.fail("expected " + what + ", found end of line");
    lines.fail("expected " + what + (value ? " to be finite" : " (a number)") + ", found " + quoted(token));
  }
  if (!tokens.at_end()) lines.fail("unexpected " + quoted(tokens.next()) + " after 'vertex x y z'");
}

// After "facet normal ...": "outer loop", n >= 3 "vertex x y z" (fanned, as
// for every polygon; the format says 3), "endloop", "endfacet". The normal is
// ignored: exporters write zero, stale or NaN normals.
void read_facet(TextLines& lines, std::size_t facet, CornerMerger& merger, std::vector<int>& triangles) {
  LineTokens loop = expect_line(lines, "outer", "'outer loop'");
  if (const std::string_view word = loop.next(); !is_keyword(word, "loop"))
    lines.fail("expected 'outer loop', found 'outer' followed by " + quoted(word));
  std::size_t corners = 0;
  int first = 0, previous = 0;
  for (;;) {
    lines.require_next("'vertex x y z' or 'endloop'");
    LineTokens tokens = fields(lines);
    const std::string_view word = tokens.next();
    if (is_keyword(word, "endloop")) break;
    if (!is_keyword(word, "vertex")) lines.fail("expected 'vertex x y z' or 'endloop', found " + quoted(word));
    double p[3];
    read_ascii_vertex(lines, tokens, facet, corners, p);
    const int v = merger.vertex(p[0], p[1], p[2]);
    if (corners == 0) first = v;
    if (corners >= 2) triangles.insert(triangles.end(), {first, previous, v});
    previous = v;
    ++corners;
  }
  if (corners < 3)
    lines.fail("facet " + std::to_string(facet) + " has " + std::to_string(corners) +
               " vertices: expected at least 3 before 'endloop'");
  expect_line(lines, "endfacet", "'endfacet'");
}

// One or more concatenated "solid ... endsolid" blocks.
TriangleMesh read_ascii(std::string_view text, const std::filesystem::path& file, const ProgressCallback& progress) {
  TextLines lines(text, file, progress, '\0');
  CornerMerger merger(0);
  std::vector<int> triangles;
  std::size_t facet = 0;
  expect_line(lines, "solid", "'solid [name]'");
  for (;;) {
    lines.require_next("'facet normal nx ny nz' or 'endsolid'");
    const std::string_view word = fields(lines).next();
    if (is_keyword(word, "endsolid")) {
      if (!lines.next()) break;
      if (const std::string_view next = fields(lines).next(); !is_keyword(next, "solid"))
        lines.fail("expected the end of the file or another 'solid', found " + quoted(next));
      continue;
    }
    if (!is_keyword(word, "facet"))
      lines.fail("expected 'facet normal nx ny nz' or 'endsolid', found " + quoted(word));
    read_facet(lines, facet++, merger, triangles);
  }
  if (progress) progress(1.0);
  return indexed_mesh(merger, triangles);
}

// ---- writing -------------------------------------------------------------

// The unit normal of face f; zero for a degenerate triangle. The edges are
// scaled first so that 1e-300 or 1e300 coordinates neither underflow nor
// overflow the cross product.
Eigen::Vector3d facet_normal(const TriangleMesh& mesh, Eigen::Index f) {
  const auto& P = mesh.vertices.positions;
  Eigen::Vector3d e1 = P.row(mesh.faces(f, 1)) - P.row(mesh.faces(f, 0));
  Eigen::Vector3d e2 = P.row(mesh.faces(f, 2)) - P.row(mesh.faces(f, 0));
  const double scale = std::max(e1.cwiseAbs().maxCoeff(), e2.cwiseAbs().maxCoeff());
  if (!(scale > 0.0) || !std::isfinite(scale)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d n = (e1 / scale).cross(e2 / scale);
  const double length = n.norm();
  return length > 0.0 && std::isfinite(length) ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

float to_float(double x, Eigen::Index vertex) {
  const auto f = static_cast<float>(x);
  if (std::isfinite(f)) return f;
  std::string message = "binary STL stores float32 coordinates, and vertex " + std::to_string(vertex) +
                        " has the coordinate ";
  append_double(message, x);
  throw InvalidInput(message + " beyond their range: write ascii STL instead");
}

std::string write_binary(const TriangleMesh& mesh) {
  if (static_cast<std::uint64_t>(mesh.face_count()) > std::numeric_limits<std::uint32_t>::max())
    throw InvalidInput("binary STL holds at most 2^32 - 1 triangles");
  std::string out = "scanstation binary STL";  // must not start with "solid", or readers take it for ascii
  out.resize(kHeaderBytes, ' ');
  out.reserve(kHeaderBytes + kCountBytes + kTriangleBytes * static_cast<std::size_t>(mesh.face_count()));
  append_binary(out, static_cast<std::uint32_t>(mesh.face_count()), std::endian::little);
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const Eigen::Vector3d n = facet_normal(mesh, f);
    for (int a = 0; a < 3; ++a) append_binary(out, static_cast<float>(n[a]), std::endian::little);
    for (int corner = 0; corner < 3; ++corner) {
      const int v = mesh.faces(f, corner);
      for (int a = 0; a < 3; ++a)
        append_binary(out, to_float(mesh.vertices.positions(v, a), v), std::endian::little);
    }
    append_binary(out, std::uint16_t{0}, std::endian::little);
  }
  return out;
}

void append_triple(std::string& out, const char* prefix, const Eigen::Vector3d& p) {
  out += prefix;
  for (int a = 0; a < 3; ++a) {
    out += ' ';
    append_double(out, p[a]);
  }
  out += '\n';
}

std::string write_ascii(const TriangleMesh& mesh) {
  std::string out = "solid scanstation\n";
  out.reserve(static_cast<std::size_t>(mesh.face_count()) * 256 + 64);
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    append_triple(out, "  facet normal", facet_normal(mesh, f));
    out += "    outer loop\n";
    for (int corner = 0; corner < 3; ++corner)
      append_triple(out, "      vertex", mesh.vertices.positions.row(mesh.faces(f, corner)).transpose());
    out += "    endloop\n  endfacet\n";
  }
  out += "endsolid scanstation\n";
  return out;
}

}  // namespace

TriangleMesh read_stl(std::string_view bytes, const std::filesystem::path& file, const ProgressCallback& progress) {
  if (bytes.empty())
    throw FormatError(FileLocation::at_byte(file, 0),
                      "file is empty: expected an ascii STL ('solid name') or a binary STL (80-byte header)");
  const bool solid = starts_with_solid(bytes);
  if (bytes.size() < kHeaderBytes + kCountBytes) {
    if (solid) return read_ascii(bytes, file, progress);
    throw FormatError(FileLocation::at_byte(file, bytes.size()),
                      "file ends early: expected an 80-byte header and a triangle count (84 bytes) for a binary "
                      "STL, or 'solid' for an ascii STL");
  }
  ByteCursor cursor(bytes, file, kHeaderBytes);
  const auto count = cursor.read<std::uint32_t>(std::endian::little, "the triangle count");
  const std::uint64_t expected = kHeaderBytes + kCountBytes + std::uint64_t{kTriangleBytes} * count;
  // Many binary exporters start the header with "solid" too: the size decides.
  if (bytes.size() == expected) return read_binary(bytes, file, count, progress);
  // Ascii STL never contains a NUL byte; a "solid" header followed by one is
  // a binary STL of the wrong size.
  if (solid && std::memchr(bytes.data(), '\0', bytes.size()) == nullptr) return read_ascii(bytes, file, progress);
  throw FormatError(FileLocation::at_byte(file, kHeaderBytes),
                    "the file size does not match the triangle count: a binary STL with " + std::to_string(count) +
                        " triangles has 84 + 50 * " + std::to_string(count) + " = " + std::to_string(expected) +
                        " bytes, this file has " + std::to_string(bytes.size()) +
                        (bytes.size() < expected ? " (truncated?)" : ""));
}

std::string write_stl(const TriangleMesh& mesh, Encoding encoding) {
  switch (encoding) {
    case Encoding::ascii:
      return write_ascii(mesh);
    case Encoding::binary_little_endian:
      return write_binary(mesh);
    case Encoding::binary_big_endian:
      break;
  }
  throw InvalidInput("STL has no big-endian variant: write binary (little endian) or ascii STL");
}

}  // namespace scanstation::io
