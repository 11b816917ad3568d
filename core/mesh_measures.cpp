#include "core/mesh_measures.h"

#include "core/unit_scale.h"

#include <Eigen/Geometry>

namespace scanstation {

namespace {
Eigen::Vector3d corner(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, Eigen::Index f, int k) {
  return V.row(F(f, k)).transpose();
}
}  // namespace

// Coordinates near 1e±160 or beyond: the squares of edge lengths (and the
// cubes of the volume's terms) leave the double range, and an area that is
// a normal double came out 0 or infinite. Measured on the copy scaled by a
// power of two and scaled back, exactly.
double surface_area(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  if (const double s = unit_scale(V); beyond_squares(s)) return std::ldexp(surface_area(V * s, F), -2 * std::ilogb(s));
  double area = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    area += 0.5 * (corner(V, F, f, 1) - corner(V, F, f, 0)).cross(corner(V, F, f, 2) - corner(V, F, f, 0)).norm();
  return area;
}

// The tetrahedra of the divergence theorem reach from the bounding box's
// centre rather than the origin: far from the origin (a scan in a turntable's
// coordinates, 1e6 off) the terms from the origin are large and cancel, and
// their rounding swamps the volume (a bunny 1e6 off gave −1773 for 0.1995).
double enclosed_volume(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  if (F.rows() == 0) return 0.0;
  if (const double s = unit_scale(V); beyond_squares(s)) return std::ldexp(enclosed_volume(V * s, F), -3 * std::ilogb(s));
  const Eigen::Vector3d o = 0.5 * (V.colwise().minCoeff() + V.colwise().maxCoeff()).transpose();
  double six = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    six += (corner(V, F, f, 0) - o).dot((corner(V, F, f, 1) - o).cross(corner(V, F, f, 2) - o));
  return six / 6.0;
}

}  // namespace scanstation
