#include "core/io/vtk.h"

#include "core/errors.h"
#include "core/io/number_text.h"

namespace scanstation::io {

std::string write_vtk_cells(const Eigen::MatrixX3d& points, const Eigen::MatrixXi& cells) {
  const Eigen::Index k = cells.cols();
  if (k != 3 && k != 4) throw InvalidInput("VTK cells: expected triangles (3 indices) or tetrahedra (4)");
  std::string out = "# vtk DataFile Version 3.0\nscanstation interior triangulation\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS ";
  append_int(out, points.rows());
  out += " double\n";
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    for (int c = 0; c < 3; ++c) {
      if (c > 0) out += ' ';
      append_double(out, points(i, c));
    }
    out += '\n';
  }
  out += "CELLS ";
  append_int(out, cells.rows());
  out += ' ';
  append_int(out, cells.rows() * (k + 1));
  out += '\n';
  for (Eigen::Index c = 0; c < cells.rows(); ++c) {
    append_int(out, k);
    for (Eigen::Index j = 0; j < k; ++j) {
      out += ' ';
      append_int(out, cells(c, j));
    }
    out += '\n';
  }
  out += "CELL_TYPES ";
  append_int(out, cells.rows());
  out += '\n';
  const std::string type = k == 3 ? "5\n" : "10\n";
  for (Eigen::Index c = 0; c < cells.rows(); ++c) out += type;
  return out;
}

}  // namespace scanstation::io
