// Lists of vertex indices as text: one face per line ("i j" or "i j k").
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <limits>

namespace scanstation::io {

/// Reads a file of `columns` integers per line in [0, count) ('#' comments
/// and blank lines skipped), e.g. faces as indices into `count` points.
/// Throws FormatError naming the line for anything else, a line that repeats
/// an earlier one as a set of indices included.
Eigen::MatrixXi read_index_list(const std::filesystem::path& path, int columns,
                                long long count = std::numeric_limits<int>::max());

}  // namespace scanstation::io
