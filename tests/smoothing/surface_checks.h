// Checks shared by the surface scheme tests.
#pragma once

#include "smoothing/bezier_surface.h"
#include "smoothing/patch_adjacency.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace scanstation::test {

/// Every patch corner that is a vertex of its macro triangle: the patch
/// normal there equals the prescribed vertex normal. Returns how many corners
/// were checked (every macro vertex of every patch that touches one).
inline std::size_t expect_interpolates(const BezierSurface& surface, const Eigen::MatrixX3d& V,
                                       const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N) {
  const Barycentric corner_parameter[3] = {Barycentric::UnitX(), Barycentric::UnitY(), Barycentric::UnitZ()};
  std::size_t checked = 0;
  for (std::size_t p = 0; p < surface.patches.size(); ++p)
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) {
        const int v = F(surface.macro[p], c);
        if (patch_corner(surface.patches[p], k) != Eigen::Vector3d(V.row(v))) continue;
        const Eigen::Vector3d n = normal_direction(surface.patches[p], corner_parameter[k]).normalized();
        EXPECT_NEAR((n - Eigen::Vector3d(N.row(v))).norm(), 0.0, 1e-9) << "patch " << p << " vertex " << v;
        ++checked;
      }
  return checked;
}

}  // namespace scanstation::test
