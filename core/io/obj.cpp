#include "core/io/obj.h"

#include "core/io/number_text.h"
#include "core/io/text_lines.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace scanstation::io {

namespace {

struct ObjData {
  std::vector<double> positions;
  std::vector<std::uint8_t> colors;  // one row per vertex; kept only when every vertex had one
  std::size_t colored = 0;
  std::vector<int> triangles;
  // A positive index may name a vertex defined further down the file; the
  // largest such index is checked once all vertices are known.
  long long forward_index = 0;
  std::size_t forward_line = 0;

  long long vertex_count() const { return static_cast<long long>(positions.size() / 3); }
};

// A binary file (a binary STL or PLY named .obj) is refused up front: its
// bytes would otherwise surface as puzzling "unknown record" lines.
void reject_binary(std::string_view text, const std::filesystem::path& file) {
  const void* nul = std::memchr(text.data(), '\0', text.size());
  if (!nul) return;
  const auto offset = static_cast<std::size_t>(static_cast<const char*>(nul) - text.data());
  const auto line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + offset, '\n'));
  throw FormatError(FileLocation::at_line(file, line), "binary data in a text OBJ file (a NUL byte at byte " +
                                                           std::to_string(offset) +
                                                           "): expected text records such as 'v x y z'");
}

// A trailing backslash continues a record on the next line; the pieces are
// joined into `joined` (only continued records pay for the copy).
std::string_view whole_record(TextLines& lines, std::string& joined) {
  std::string_view line = lines.line();
  if (line.back() != '\\') return line;
  joined.clear();
  while (!line.empty() && line.back() == '\\') {
    joined.append(line.substr(0, line.size() - 1)).push_back(' ');
    if (!lines.next()) return joined;
    line = lines.line();
  }
  return joined.append(line);
}

// The tokens of one record and the line that names it (the first, for a
// continued record). LineTokens' own location stays empty: copying the file
// path for every line would cost more than parsing the line.
struct Record {
  LineTokens tokens;
  const std::filesystem::path& file;
  std::size_t line;

  Record(std::string_view text, const std::filesystem::path& f, std::size_t l)
      : tokens(text, FileLocation{}), file(f), line(l) {}
  [[noreturn]] void fail(const std::string& message) const {
    throw FormatError(FileLocation::at_line(file, line), message);
  }
};

template <typename Describe>
double finite_number(Record& record, std::string_view token, Describe&& what) {
  if (const auto value = parse_double(token); value && std::isfinite(*value)) return *value;
  if (token.empty()) record.fail("expected " + what() + ", found end of line");
  if (!parse_double(token)) record.fail("expected " + what() + " (a number), found " + quoted(token));
  record.fail("expected " + what() + " to be finite, found " + quoted(token));
}

// "v x y z [w] [r g b]": w is a rational-curve weight, meaningless for a mesh.
void read_vertex(Record& record, ObjData& data) {
  static const char* const kNames[7] = {"x coordinate", "y coordinate", "z coordinate", "w coordinate",
                                        "red component", "green component", "blue component"};
  const long long vertex = data.vertex_count() + 1;
  std::array<std::string_view, 8> parts;
  std::size_t n = 0;
  while (n < parts.size() && !(parts[n] = record.tokens.next()).empty()) ++n;
  if (n < 3 || n == 5 || n > 7)
    record.fail("expected 'v x y z [w] [r g b]' (3, 4, 6 or 7 numbers) for vertex " + std::to_string(vertex) +
                ", found " + (n > 7 ? "more than 7" : std::to_string(n)));
  const bool has_w = n == 4 || n == 7;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t role = i < 3 || has_w ? i : i + 1;
    const auto what = [&] { return std::string("the ") + kNames[role] + " of vertex " + std::to_string(vertex); };
    const double value = finite_number(record, parts[i], what);
    if (role < 3) data.positions.push_back(value);
    if (role < 4) continue;
    if (value < 0.0 || value > 1.0) record.fail("expected " + what() + " in 0..1, found " + quoted(parts[i]));
    data.colors.push_back(static_cast<std::uint8_t>(std::lround(value * 255.0)));
  }
  if (n >= 6) ++data.colored;
  else data.colors.insert(data.colors.end(), 3, 0);
}

// The texture and normal references after a corner's vertex index ("",
// "/vt", "//vn", "/vt/vn") are skipped, but must be integers when present.
bool valid_references(std::string_view rest) {
  if (rest.empty()) return true;
  rest.remove_prefix(1);  // the '/'
  const std::size_t slash = rest.find('/');
  const std::string_view vt = rest.substr(0, slash);
  const std::string_view vn = slash == std::string_view::npos ? std::string_view() : rest.substr(slash + 1);
  const auto is_index = [](std::string_view part) { return part.empty() || parse_int(part).has_value(); };
  return is_index(vt) && is_index(vn) && vn.find('/') == std::string_view::npos;
}

// The vertex of a corner "v", "v/vt", "v//vn" or "v/vt/vn", 0-based.
int corner_vertex(Record& record, std::string_view corner, std::size_t k, ObjData& data) {
  const auto about = [&](const std::string& problem) {
    return "corner " + std::to_string(k + 1) + " " + quoted(corner) + " of the face: " + problem;
  };
  const std::size_t slash = std::min(corner.find('/'), corner.size());
  const auto index = parse_int(corner.substr(0, slash));
  if (!index || !valid_references(corner.substr(slash)))
    record.fail(about("expected 'v', 'v/vt', 'v//vn' or 'v/vt/vn' with integer indices"));
  if (*index == 0) record.fail(about("vertex index 0 is invalid: expected 1-based or negative indices"));
  const long long known = data.vertex_count();
  if (*index < 0 && -*index > known)
    record.fail(about("vertex index " + std::to_string(*index) + " is out of range: only " + std::to_string(known) +
                      " vertices are defined before it"));
  if (*index > INT_MAX) record.fail(about("vertex index " + std::to_string(*index) + " is out of range"));
  if (*index > known && *index > data.forward_index) {
    data.forward_index = *index;
    data.forward_line = record.line;
  }
  return static_cast<int>(*index < 0 ? known + *index : *index - 1);
}

// "f c1 c2 c3 ...": the polygon is fan-triangulated (1, k, k+1).
void read_face(Record& record, ObjData& data) {
  int first = 0, previous = 0;
  std::size_t k = 0;
  for (std::string_view corner = record.tokens.next(); !corner.empty(); corner = record.tokens.next(), ++k) {
    const int v = corner_vertex(record, corner, k, data);
    if (k == 0) first = v;
    if (k >= 2) data.triangles.insert(data.triangles.end(), {first, previous, v});
    previous = v;
  }
  if (k < 3) record.fail("face with " + std::to_string(k) + " corner(s): expected at least 3");
}

void read_record(Record& record, ObjData& data) {
  const std::string_view keyword = record.tokens.next();
  if (keyword == "v") return read_vertex(record, data);
  if (keyword == "f" || keyword == "fo") return read_face(record, data);  // "fo" is the pre-3.0 face keyword
  // vn, vt, vp, g, o, s, l, p, usemtl, mtllib, cstype, curv, surf, ...: no
  // bearing on a triangle mesh. Anything not starting with a letter is not OBJ.
  if (!std::isalpha(static_cast<unsigned char>(keyword.front())))
    record.fail("expected an OBJ record keyword such as 'v' or 'f', found " + quoted(keyword));
}

template <typename T>
Eigen::Matrix<T, Eigen::Dynamic, 3> rows_of(const std::vector<T>& values) {
  using RowMajor = Eigen::Matrix<T, Eigen::Dynamic, 3, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(values.data(), static_cast<Eigen::Index>(values.size() / 3), 3);
}

void check_complete(const TextLines& lines, const ObjData& data) {
  if (data.positions.empty() && data.triangles.empty())
    throw FormatError(FileLocation::at_line(lines.file(), lines.line_number() + 1),
                      "unexpected end of file: expected at least one 'v' record");
  if (data.forward_index > data.vertex_count())
    throw FormatError(FileLocation::at_line(lines.file(), data.forward_line),
                      "vertex index " + std::to_string(data.forward_index) + " is out of range: the file has " +
                          std::to_string(data.vertex_count()) + " vertices");
}

}  // namespace

TriangleMesh read_obj(std::string_view text, const std::filesystem::path& file, const ProgressCallback& progress) {
  reject_binary(text, file);
  TextLines lines(text, file, progress);
  if (!lines.next())
    throw FormatError(FileLocation::at_line(file, 1), "file is empty: expected at least one 'v' record");
  ObjData data;
  std::string joined;
  do {
    const std::size_t first_line = lines.line_number();
    const std::string_view text_of_record = whole_record(lines, joined);
    Record record(text_of_record.substr(0, text_of_record.find('#')), file, first_line);
    if (!record.tokens.at_end()) read_record(record, data);
  } while (lines.next());
  check_complete(lines, data);

  TriangleMesh mesh;
  mesh.vertices.positions = rows_of(data.positions);
  if (data.colored > 0 && data.colored == static_cast<std::size_t>(data.vertex_count()))
    mesh.vertices.colors = rows_of(data.colors);
  mesh.faces = rows_of(data.triangles);
  if (progress) progress(1.0);
  return mesh;
}

std::string write_obj(const TriangleMesh& mesh) {
  const PointCloud& v = mesh.vertices;
  if (v.has_colors() && v.colors.rows() != v.size())
    throw InvalidInput("write_obj: the colours must have one row per vertex");
  if (v.has_normals() && v.normals.rows() != v.size())
    throw InvalidInput("write_obj: the normals must have one row per vertex");
  std::string out = "# written by scanstation\n";
  out.reserve(static_cast<std::size_t>(v.size()) * 48 + static_cast<std::size_t>(mesh.face_count()) * 24 + 32);
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    out += 'v';
    for (int a = 0; a < 3; ++a) {
      out += ' ';
      append_double(out, v.positions(i, a));
    }
    for (int a = 0; v.has_colors() && a < 3; ++a) {
      out += ' ';
      append_double(out, v.colors(i, a) / 255.0);  // reads back to the same byte: round(c / 255 * 255) = c
    }
    out += '\n';
  }
  // Vertex normals as `vn`, one per vertex with the same index (f a//a ...).
  for (Eigen::Index i = 0; v.has_normals() && i < v.size(); ++i) {
    out += "vn";
    for (int a = 0; a < 3; ++a) {
      out += ' ';
      append_double(out, v.normals(i, a));
    }
    out += '\n';
  }
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    out += 'f';
    for (int a = 0; a < 3; ++a) {
      out += ' ';
      append_int(out, mesh.faces(f, a) + 1LL);
      if (v.has_normals()) {
        out += "//";
        append_int(out, mesh.faces(f, a) + 1LL);
      }
    }
    out += '\n';
  }
  return out;
}

}  // namespace scanstation::io
