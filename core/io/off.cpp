#include "core/io/off.h"

#include "core/io/number_text.h"
#include "core/io/text_lines.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <vector>

namespace scanstation::io {

namespace {

constexpr std::string_view kKeywords = "the OFF header keyword ('OFF', 'COFF', 'NOFF' or 'CNOFF')";

// The fewest bytes a vertex line ("0 0 0\n") and a face line ("3 0 1 2\n")
// can take: a declared count is trusted for reserve() only as far as the
// file could hold it, so a corrupt header cannot trigger a huge allocation.
constexpr std::size_t kMinVertexLineBytes = 6;
constexpr std::size_t kMinFaceLineBytes = 8;

struct OffHeader {
  bool normals = false;
  bool colors = false;
  long long vertex_count = 0;
  long long face_count = 0;
};

// What the vertex and face lines accumulate, row-major.
struct OffData {
  std::vector<double> positions;
  std::vector<double> normals;
  std::vector<std::uint8_t> colors;
  std::vector<int> triangles;
};

// '#' also starts a comment after data ("1 2 3 # top"), not only at the start
// of a line, which TextLines already skips.
std::string_view data_of(const TextLines& lines) {
  const std::string_view line = lines.line();
  return line.substr(0, line.find('#'));
}

LineTokens located_tokens(const TextLines& lines) { return LineTokens(data_of(lines), lines.here()); }

// The tokens of one vertex or face line. Their errors go through
// TextLines::fail: a LineTokens of its own location would copy the file path
// for every line, which costs more than parsing the line.
struct Fields {
  LineTokens tokens;
  const TextLines& lines;

  explicit Fields(const TextLines& l) : tokens(data_of(l), FileLocation{}), lines(l) {}
  [[noreturn]] void fail(const std::string& message) const { lines.fail(message); }
};

// [C][N]OFF in either letter order; "ST", "4" and "n" variants are not read.
bool parse_keyword(std::string_view word, OffHeader& header) {
  if (word.size() < 3 || word.substr(word.size() - 3) != "OFF") return false;
  for (const char c : word.substr(0, word.size() - 3)) {
    bool* flag = c == 'C' ? &header.colors : c == 'N' ? &header.normals : nullptr;
    if (!flag || *flag) return false;  // an unknown or a repeated letter
    *flag = true;
  }
  return true;
}

// Binary garbage would make an unreadable (or NUL-truncated) message.
std::string shown(std::string_view token) {
  const bool binary = std::any_of(token.begin(), token.end(),
                                  [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
  return binary ? std::string("binary data") : quoted(token);
}

OffHeader read_header(TextLines& lines) {
  if (!lines.next())
    throw FormatError(FileLocation::at_line(lines.file(), 1), "file is empty: expected " + std::string(kKeywords));
  OffHeader header;
  LineTokens tokens = located_tokens(lines);
  const std::string_view word = tokens.next();
  if (!parse_keyword(word, header)) tokens.fail("expected " + std::string(kKeywords) + ", found " + shown(word));
  // The counts may follow the keyword on its own line ("OFF 8 6 0").
  if (tokens.at_end()) {
    lines.require_next("the counts line 'vertices faces edges'");
    tokens = located_tokens(lines);
  } else if (LineTokens probe = tokens; probe.next() == "BINARY") {
    tokens.fail("binary OFF is not supported: expected the counts 'vertices faces edges' after " + quoted(word));
  }
  header.vertex_count = tokens.next_int("the vertex count", 0, INT_MAX);
  header.face_count = tokens.next_int("the face count", 0, INT_MAX);
  if (!tokens.at_end()) tokens.next_int("the edge count", 0, LLONG_MAX);  // unused by every reader
  tokens.expect_end("the counts 'vertices faces edges'");
  return header;
}

// Builds the message only when the token is bad, so the hot loop never
// allocates.
template <typename Describe>
double finite_number(Fields& line, Describe&& what) {
  const std::string_view token = line.tokens.next();
  if (const auto value = parse_double(token); value && std::isfinite(*value)) return *value;
  if (token.empty()) line.fail("expected " + what() + ", found end of line");
  if (!parse_double(token)) line.fail("expected " + what() + " (a number), found " + quoted(token));
  line.fail("expected " + what() + " to be finite, found " + quoted(token));
}

template <typename Describe>
void read_triple(Fields& line, const char* const (&names)[3], Describe&& of_what, std::vector<double>& out) {
  for (const char* name : names)
    out.push_back(finite_number(line, [&] { return std::string("the ") + name + " " + of_what(); }));
}

// Geomview allows integers 0..255 or floats 0..1; a '.' or an exponent in any
// component marks the float form, so "1 1 1" is read as integers.
void read_color(Fields& line, long long vertex, std::vector<std::uint8_t>& out) {
  const auto where = [&] { return "the colour 'r g b [a]' of vertex " + std::to_string(vertex); };
  std::string_view parts[5];
  std::size_t n = 0;
  while (n < 5 && !(parts[n] = line.tokens.next()).empty()) ++n;
  if (n < 3 || n > 4) line.fail("expected " + where() + ", found " + std::to_string(n) + " value(s)");
  const bool floats = std::any_of(parts, parts + n, [](std::string_view p) {
    return p.find_first_of(".eE") != std::string_view::npos;
  });
  for (std::size_t i = 0; i < n; ++i) {
    const auto as_int = floats ? std::nullopt : parse_int(parts[i]);
    const auto as_double = floats ? parse_double(parts[i]) : std::nullopt;
    if (as_int && *as_int >= 0 && *as_int <= 255) {
      if (i < 3) out.push_back(static_cast<std::uint8_t>(*as_int));
    } else if (as_double && *as_double >= 0.0 && *as_double <= 1.0) {
      if (i < 3) out.push_back(static_cast<std::uint8_t>(std::lround(*as_double * 255.0)));
    } else {
      line.fail("expected " + where() + " as integers 0..255 or numbers 0..1, found " + quoted(parts[i]));
    }
  }
}

void read_vertices(TextLines& lines, const OffHeader& header, OffData& data) {
  static const char* const kAxes[3] = {"x coordinate", "y coordinate", "z coordinate"};
  static const char* const kNormal[3] = {"normal x", "normal y", "normal z"};
  for (long long i = 0; i < header.vertex_count; ++i) {
    if (!lines.next())
      lines.require_next("vertex " + std::to_string(i) + " of " + std::to_string(header.vertex_count));
    Fields line(lines);
    const auto of_vertex = [&] { return "of vertex " + std::to_string(i); };
    read_triple(line, kAxes, of_vertex, data.positions);
    if (header.normals) read_triple(line, kNormal, of_vertex, data.normals);
    if (header.colors) read_color(line, i, data.colors);
    if (!line.tokens.at_end())
      line.fail("unexpected " + quoted(line.tokens.next()) + " after vertex " + std::to_string(i) +
                (header.colors ? " (" : " (colours need the keyword 'COFF'; or ") + "the header's count of " +
                std::to_string(header.vertex_count) + " vertices is more than the file holds, and the faces start here)");
  }
}

// "n i0 ... in-1 [colour]": the polygon is fan-triangulated (0, k, k+1); the
// colour is ignored since TriangleMesh has no face attributes.
void read_face(Fields& line, long long face, long long vertex_count, std::vector<int>& triangles) {
  const auto name = [&] { return "face " + std::to_string(face); };
  const std::string_view count_token = line.tokens.next();
  const auto corners = parse_int(count_token);
  if (!corners) line.fail("expected the corner count of " + name() + " (an integer), found " + shown(count_token));
  if (*corners < 3) line.fail(name() + " has " + std::to_string(*corners) + " corner(s): expected at least 3");
  int first = 0, previous = 0;
  for (long long k = 0; k < *corners; ++k) {  // *corners may be absurd: the line runs out first
    const std::string_view token = line.tokens.next();
    const auto index = parse_int(token);
    if (!index)
      line.fail("expected the vertex index of corner " + std::to_string(k) + " of " + name() + " (" +
                std::to_string(*corners) + " corners), found " + (token.empty() ? "end of line" : quoted(token)));
    if (*index < 0 || *index >= vertex_count)
      line.fail(name() + ": vertex index " + std::to_string(*index) + " (corner " + std::to_string(k) +
                ") is out of range: expected 0.." + std::to_string(vertex_count - 1) + " for " +
                std::to_string(vertex_count) + " vertices");
    const int v = static_cast<int>(*index);
    if (k == 0) first = v;
    if (k >= 2) triangles.insert(triangles.end(), {first, previous, v});
    previous = v;
  }
}

void read_faces(TextLines& lines, const OffHeader& header, OffData& data) {
  for (long long f = 0; f < header.face_count; ++f) {
    if (!lines.next()) lines.require_next("face " + std::to_string(f) + " of " + std::to_string(header.face_count));
    Fields line(lines);
    read_face(line, f, header.vertex_count, data.triangles);
  }
  if (lines.next())
    lines.fail("expected the end of the file after the last of " + std::to_string(header.face_count) +
               " faces, found " + shown(located_tokens(lines).next()));
}

template <typename T>
Eigen::Matrix<T, Eigen::Dynamic, 3> rows_of(const std::vector<T>& values) {
  using RowMajor = Eigen::Matrix<T, Eigen::Dynamic, 3, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(values.data(), static_cast<Eigen::Index>(values.size() / 3), 3);
}

}  // namespace

TriangleMesh read_off(std::string_view text, const std::filesystem::path& file, const ProgressCallback& progress) {
  TextLines lines(text, file, progress);
  const OffHeader header = read_header(lines);
  OffData data;
  const std::size_t rest = text.size() - std::min(text.size(), lines.offset());
  const auto vertices = std::min<std::size_t>(header.vertex_count, rest / kMinVertexLineBytes);
  data.positions.reserve(3 * vertices);
  if (header.normals) data.normals.reserve(3 * vertices);
  if (header.colors) data.colors.reserve(3 * vertices);
  data.triangles.reserve(3 * std::min<std::size_t>(header.face_count, rest / kMinFaceLineBytes));
  read_vertices(lines, header, data);
  read_faces(lines, header, data);

  TriangleMesh mesh;
  mesh.vertices.positions = rows_of(data.positions);
  mesh.vertices.normals = rows_of(data.normals);
  mesh.vertices.colors = rows_of(data.colors);
  mesh.faces = rows_of(data.triangles);
  if (progress) progress(1.0);
  return mesh;
}

std::string write_off(const TriangleMesh& mesh) {
  const PointCloud& v = mesh.vertices;
  if ((v.has_normals() && v.normals.rows() != v.size()) || (v.has_colors() && v.colors.rows() != v.size()))
    throw InvalidInput("write_off: the normals and colours must have one row per vertex");
  std::string out;
  out.reserve(static_cast<std::size_t>(v.size()) * 40 + static_cast<std::size_t>(mesh.face_count()) * 24 + 32);
  out += v.has_colors() ? "C" : "";
  out += v.has_normals() ? "NOFF\n" : "OFF\n";
  append_int(out, v.size());
  out += ' ';
  append_int(out, mesh.face_count());
  out += " 0\n";
  append_ascii_vertices_and_faces(out, mesh);
  return out;
}

}  // namespace scanstation::io
