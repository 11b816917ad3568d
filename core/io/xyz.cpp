#include "core/io/xyz.h"

#include "core/io/number_text.h"
#include "core/io/text_lines.h"

#include <algorithm>
#include <cctype>
#include <vector>

namespace scanstation::io {

namespace {
const char* const kAxis[6] = {"x", "y", "z", "nx", "ny", "nz"};

// A first line of column names ("x,y,z" in CSV exports) is not data.
bool is_header_line(LineTokens tokens) {
  const std::string_view first = tokens.next();
  return !first.empty() && !parse_double(first).has_value() && (std::isalpha(static_cast<unsigned char>(first[0])) ||
                                                                first[0] == '"' || first[0] == '_');
}

std::size_t checked_columns(const TextLines& lines, std::size_t columns) {
  if (columns == 2 || columns == 3 || columns == 6) return columns;
  lines.fail("expected 2 (x y), 3 (x y z) or 6 (x y z nx ny nz) numbers per line, found " + std::to_string(columns));
}
}  // namespace

PointCloud read_xyz(std::string_view text, const std::filesystem::path& file, const ProgressCallback& progress) {
  TextLines lines(text, file, progress);
  if (!lines.next()) throw FormatError(FileLocation::whole(file), "file is empty: expected lines of 'x y z' numbers");
  if (lines.line_number() == 1 && is_header_line(lines.tokens(true)) && !lines.next())
    throw FormatError(FileLocation::whole(file), "no points after the header line: expected lines of 'x y z' numbers");

  const std::size_t columns = checked_columns(lines, lines.tokens(true).remaining());
  const std::size_t first_line = lines.line_number();
  std::vector<double> values;
  // Bytes per value are at least two ("0 "), which bounds a sane reserve.
  values.reserve(std::min<std::size_t>(text.size() / 2, std::size_t{1} << 26));
  do {
    LineTokens tokens = lines.tokens(true);
    const std::size_t found = tokens.remaining();
    if (found != columns)
      lines.fail("expected " + std::to_string(columns) + " numbers per line (as on line " +
                 std::to_string(first_line) + "), found " + std::to_string(found));
    for (std::size_t c = 0; c < columns; ++c) values.push_back(tokens.next_double(kAxis[c]));
  } while (lines.next());

  const Eigen::Index n = static_cast<Eigen::Index>(values.size() / columns);
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> table(
      values.data(), n, static_cast<Eigen::Index>(columns));
  PointCloud cloud;
  cloud.positions = Eigen::MatrixX3d::Zero(n, 3);
  if (columns == 2) {
    cloud.positions.leftCols(2) = table;
    cloud.dimension = 2;
  } else {
    cloud.positions = table.leftCols(3);
  }
  if (columns == 6) cloud.normals = table.rightCols(3);
  return cloud;
}

std::string write_xyz(const PointCloud& points, char separator) {
  std::string out;
  out.reserve(static_cast<std::size_t>(points.size()) * (points.has_normals() ? 120 : 60));
  const Eigen::Index coordinates = points.dimension == 2 ? 2 : 3;
  for (Eigen::Index i = 0; i < points.size(); ++i) {
    for (Eigen::Index c = 0; c < coordinates; ++c) {
      if (c > 0) out += separator;
      append_double(out, points.positions(i, c));
    }
    if (points.has_normals() && points.dimension != 2)
      for (Eigen::Index c = 0; c < 3; ++c) {
        out += separator;
        append_double(out, points.normals(i, c));
      }
    out += '\n';
  }
  return out;
}

}  // namespace scanstation::io
