#include "smoothing/oscillation.h"

#include "smoothing/blockwise.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace scanstation {

namespace {

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

}  // namespace

Oscillation oscillation(const BezierSurface& surface, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                        int samples_per_edge) {
  Oscillation result;
  std::size_t count = 0;
  const int n = samples_per_edge;
  // The Bernstein weights 3!/(i!j!k!) u^i v^j w^k of the grid points, once:
  // a sample is then one row of weights times the ten control points.
  std::vector<std::array<double, 10>> weights;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(n - i - j) / n, v = double(i) / n, w = double(j) / n;
      std::array<double, 10>& row = weights.emplace_back();
      for (int a = 0; a <= 3; ++a)
        for (int b = 0; a + b <= 3; ++b) {
          const int c = 3 - a - b;
          const double multinomial = 6.0 / (std::tgamma(a + 1) * std::tgamma(b + 1) * std::tgamma(c + 1));
          row[control_index(a, b, c)] = multinomial * std::pow(u, a) * std::pow(v, b) * std::pow(w, c);
        }
    }
  // Blocks of patches on all cores: the same mean for any number of threads.
  constexpr std::size_t kBlock = 4096;
  struct Partial {
    double max = 0.0, sum = 0.0, distance = 0.0;
    std::size_t count = 0;
  };
  const auto visit = [&](std::size_t begin, std::size_t end, Partial& part) {
    for (std::size_t p = begin; p < end; ++p) {
      const int f = surface.macro[p];
      const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
      const double edge_length = ((b - a).norm() + (c - b).norm() + (a - c).norm()) / 3.0;
      if (!(edge_length > 0.0)) continue;
      const CubicTriangle& patch = surface.patches[p];
      for (const std::array<double, 10>& row : weights) {
        Eigen::Vector3d x = row[0] * patch[0];
        for (int k = 1; k < 10; ++k) x += row[k] * patch[k];
        const double distance = (x - closest_on_triangle(x, a, b, c)).norm(), relative = distance / edge_length;
        part.distance = std::max(part.distance, distance);
        part.max = std::max(part.max, relative);
        part.sum += relative;
        ++part.count;
      }
    }
  };
  const auto partial = blockwise<Partial>(surface.patches.size(), kBlock, visit);
  for (const Partial& part : partial) {
    result.max_relative = std::max(result.max_relative, part.max);
    result.max_distance = std::max(result.max_distance, part.distance);
    result.mean_relative += part.sum;
    count += part.count;
  }
  if (count > 0) result.mean_relative /= double(count);
  return result;
}

}  // namespace scanstation
