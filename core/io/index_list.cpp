#include "core/io/index_list.h"

#include "core/io/file_access.h"
#include "core/io/text_lines.h"

#include <algorithm>
#include <limits>
#include <map>
#include <vector>

namespace scanstation::io {

Eigen::MatrixXi read_index_list(const std::filesystem::path& path, int columns, long long count) {
  const std::string text = read_file(path);
  TextLines lines(text, path);
  std::vector<int> values;
  std::map<std::vector<int>, std::size_t> seen;  // the sorted indices of each line, and the line
  while (lines.next()) {
    LineTokens tokens = lines.tokens(true);
    std::vector<int> row;
    for (int c = 0; c < columns; ++c)
      row.push_back(static_cast<int>(tokens.next_int("vertex index " + std::to_string(c + 1) + " of " +
                                                         std::to_string(columns),
                                                     0, std::min<long long>(count, std::numeric_limits<int>::max()) - 1)));
    tokens.expect_end(std::to_string(columns) + " vertex indices");
    values.insert(values.end(), row.begin(), row.end());
    std::sort(row.begin(), row.end());
    if (const auto [at, fresh] = seen.emplace(row, lines.line_number()); !fresh)
      throw FormatError(tokens.where(), "the same indices as line " + std::to_string(at->second));
  }
  if (values.empty()) throw FormatError(FileLocation::whole(path), "file is empty: expected lines of vertex indices");
  Eigen::MatrixXi out(static_cast<Eigen::Index>(values.size()) / columns, columns);
  for (Eigen::Index r = 0; r < out.rows(); ++r)
    for (int c = 0; c < columns; ++c) out(r, c) = values[static_cast<std::size_t>(r * columns + c)];
  return out;
}

}  // namespace scanstation::io
