// Lists of vertex indices as text: one face per line ("i j" or "i j k").
#pragma once

#include <Eigen/Core>
#include <filesystem>

namespace scanstation::io {

/// Reads a file of `columns` non-negative integers per line ('#' comments and
/// blank lines skipped). Throws FormatError naming the line for anything else.
Eigen::MatrixXi read_index_list(const std::filesystem::path& path, int columns);

}  // namespace scanstation::io
