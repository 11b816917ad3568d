#include "smoothing/normals_apart.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace scanstation {

namespace {

using Octic = std::array<double, 9>;

bool halves_reach_zero(const Octic& b, int depth) {
  if (b[0] <= 0.0 || b[8] <= 0.0) return true;
  if (*std::min_element(b.begin(), b.end()) > 0.0 || depth == 0) return false;
  Octic left, right, level = b;  // de Casteljau at ½
  for (int r = 0; r < 9; ++r) {
    left[r] = level[0];
    right[8 - r] = level[8 - r];
    for (int k = 0; k < 8 - r; ++k) level[k] = (level[k] + level[k + 1]) / 2.0;
  }
  return halves_reach_zero(left, depth - 1) || halves_reach_zero(right, depth - 1);
}

}  // namespace

// The product of Bernstein polynomials of degrees m and n: the coefficient of
// B^{m+n}_k is Σ_{i+j=k} C(m,i) C(n,j) / C(m+n,k) a_i b_j.
Quartic cross_product(const Eigen::Vector3d* a, const Eigen::Vector3d* b) {
  static constexpr double c2[3] = {1, 2, 1}, c4[5] = {1, 4, 6, 4, 1};
  Quartic n;
  n.fill(Eigen::Vector3d::Zero());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) n[i + j] += (c2[i] * c2[j] / c4[i + j]) * a[i].cross(b[j]);
  return n;
}

bool reaches_zero(const Quartic& p, const Quartic& q) {
  static constexpr double c4[5] = {1, 4, 6, 4, 1}, c8[9] = {1, 8, 28, 56, 70, 56, 28, 8, 1};
  Octic g{};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) g[i + j] += (c4[i] * c4[j] / c8[i + j]) * p[i].dot(q[j]);
  return halves_reach_zero(g, 16);
}

}  // namespace scanstation
