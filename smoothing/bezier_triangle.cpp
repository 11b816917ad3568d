#include "smoothing/bezier_triangle.h"

#include "core/unit_scale.h"

#include <Eigen/Geometry>

namespace scanstation {

namespace {

// The blossom of a cubic triangle: de Casteljau with a different parameter
// on each of the three levels. P[a,a,a] = P(a).
Eigen::Vector3d blossom(const CubicTriangle& patch, const Barycentric& a, const Barycentric& b,
                        const Barycentric& c) {
  return blossom_level(blossom_level(blossom_level(patch, a), b), c);
}

}  // namespace

QuadraticNet blossom_level(const CubicTriangle& patch, const Barycentric& a) {
  QuadraticNet quadratic;
  for (int i = 0; i <= 2; ++i)
    for (int j = 0; j + i <= 2; ++j) {
      const int k = 2 - i - j;
      quadratic[(2 - i) * (3 - i) / 2 + k] = a[0] * patch[control_index(i + 1, j, k)] +
                                             a[1] * patch[control_index(i, j + 1, k)] +
                                             a[2] * patch[control_index(i, j, k + 1)];
    }
  return quadratic;
}

LinearNet blossom_level(const QuadraticNet& q, const Barycentric& b) {
  // q in the order b200, b110, b101, b020, b011, b002.
  return {b[0] * q[0] + b[1] * q[1] + b[2] * q[2],   // b100
          b[0] * q[1] + b[1] * q[3] + b[2] * q[4],   // b010
          b[0] * q[2] + b[1] * q[4] + b[2] * q[5]};  // b001
}

Eigen::Vector3d evaluate(const CubicTriangle& patch, const Barycentric& uvw) {
  return blossom(patch, uvw, uvw, uvw);
}

Eigen::Vector3d directional_derivative(const CubicTriangle& patch, const Barycentric& uvw, const Eigen::Vector3d& d) {
  // Equation (8.6): n · P[d, x, x] for a direction d (coordinates summing to 0).
  return 3.0 * blossom(patch, d, uvw, uvw);
}

Eigen::Vector3d normal_direction(const CubicTriangle& patch, const Barycentric& uvw) {
  return directional_derivative(patch, uvw, {-1.0, 1.0, 0.0}).cross(directional_derivative(patch, uvw, {-1.0, 0.0, 1.0}));
}

namespace {
// The normal's direction with the derivatives and their product kept near
// unit length (scaled_cross): coordinates near 1e150 or 1e-150 gave a zero
// normal. Elsewhere the unit normal is the same to the bit.
Eigen::Vector3d scaled_normal_direction(const CubicTriangle& patch, const Barycentric& uvw) {
  return scaled_cross(directional_derivative(patch, uvw, {-1.0, 1.0, 0.0}),
                      directional_derivative(patch, uvw, {-1.0, 0.0, 1.0}));
}
}  // namespace

Eigen::Vector3d unit_normal(const CubicTriangle& patch, const Barycentric& uvw) {
  Eigen::Vector3d n = scaled_normal_direction(patch, uvw);
  if (n.squaredNorm() == 0.0) n = scaled_normal_direction(patch, uvw + 1e-6 * (Barycentric::Constant(1.0 / 3.0) - uvw));
  return n.squaredNorm() > 0.0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
}

CubicTriangle subpatch(const CubicTriangle& patch, const Barycentric& r0, const Barycentric& r1,
                       const Barycentric& r2) {
  const std::array<const Barycentric*, 3> corner{&r0, &r1, &r2};
  CubicTriangle result;
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; i + j <= 3; ++j) {
      const int k = 3 - i - j;
      std::array<const Barycentric*, 3> args;
      int slot = 0;
      for (int n = 0; n < i; ++n) args[slot++] = corner[0];
      for (int n = 0; n < j; ++n) args[slot++] = corner[1];
      for (int n = 0; n < k; ++n) args[slot++] = corner[2];
      result[control_index(i, j, k)] = blossom(patch, *args[0], *args[1], *args[2]);
    }
  return result;
}

}  // namespace scanstation
