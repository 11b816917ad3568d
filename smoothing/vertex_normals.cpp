#include "smoothing/vertex_normals.h"

#include "core/errors.h"

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace scanstation {

Eigen::MatrixX3d vertex_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, NormalWeighting weighting) {
  Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(V.rows(), 3);
  std::vector<char> in_a_face(static_cast<std::size_t>(V.rows()), 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int corner = 0; corner < 3; ++corner) in_a_face[static_cast<std::size_t>(F(f, corner))] = 1;
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d cross = (b - a).cross(c - a);  // twice the area times the unit normal
    const double twice_area = cross.norm();
    if (twice_area == 0.0) continue;
    Eigen::Vector3d weighted = cross;
    if (weighting == NormalWeighting::uniform) weighted = cross / twice_area;
    if (weighting == NormalWeighting::inverse_area) weighted = 2.0 * cross / (twice_area * twice_area);
    for (int corner = 0; corner < 3; ++corner) N.row(F(f, corner)) += weighted.transpose();
  }
  for (Eigen::Index v = 0; v < N.rows(); ++v) {
    if (!in_a_face[static_cast<std::size_t>(v)]) continue;  // not on the surface: no normal, zero
    const double length = N.row(v).norm();
    // A needle-thin spike (a stray point the boundary reaches, its faces
    // long and nearly parallel) cancels exactly under the area weighting;
    // weighing each face alike gives its tip a direction.
    if (!(length > 0.0))
      throw InvalidInput("vertex " + std::to_string(v) +
                         ": no surface normal (its faces have no area, or their normals cancel" +
                         (weighting == NormalWeighting::uniform
                              ? std::string(")")
                              : std::string(": a needle-thin spike? --normals uniform weighs each face alike)")));
    N.row(v) /= length;
  }
  return N;
}

}  // namespace scanstation
