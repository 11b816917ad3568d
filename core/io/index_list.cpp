#include "core/io/index_list.h"

#include "core/io/file_access.h"
#include "core/io/text_lines.h"

#include <limits>
#include <vector>

namespace scanstation::io {

Eigen::MatrixXi read_index_list(const std::filesystem::path& path, int columns) {
  const std::string text = read_file(path);
  TextLines lines(text, path);
  std::vector<int> values;
  while (lines.next()) {
    LineTokens tokens = lines.tokens(true);
    for (int c = 0; c < columns; ++c)
      values.push_back(static_cast<int>(tokens.next_int("vertex index " + std::to_string(c + 1) + " of " +
                                                            std::to_string(columns),
                                                        0, std::numeric_limits<int>::max())));
    tokens.expect_end(std::to_string(columns) + " vertex indices");
  }
  if (values.empty()) throw FormatError(FileLocation::whole(path), "file is empty: expected lines of vertex indices");
  Eigen::MatrixXi out(static_cast<Eigen::Index>(values.size()) / columns, columns);
  for (Eigen::Index r = 0; r < out.rows(); ++r)
    for (int c = 0; c < columns; ++c) out(r, c) = values[static_cast<std::size_t>(r * columns + c)];
  return out;
}

}  // namespace scanstation::io
