#include "reconstruct/shadow_embedding.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

namespace scanstation {

bool embedded_over_axis(const Eigen::MatrixX3d& P, const std::vector<std::array<int, 3>>& faces,
                        const std::vector<int>& loop, const Eigen::Vector3d& normal) {
  using Kernel = CGAL::Epick;
  int k = 0;
  normal.cwiseAbs().maxCoeff(&k);
  if (!(normal[k] != 0.0)) return false;
  const int i = (k + 1) % 3, j = (k + 2) % 3;  // (i, j, k) a right-handed frame
  const auto shadow = [&](int v) { return Kernel::Point_2(P(v, i), P(v, j)); };
  const CGAL::Orientation turn = normal[k] > 0 ? CGAL::COUNTERCLOCKWISE : CGAL::CLOCKWISE;
  for (const auto& t : faces)
    if (CGAL::orientation(shadow(t[0]), shadow(t[1]), shadow(t[2])) != turn) return false;
  std::vector<Kernel::Point_2> polygon;
  polygon.reserve(loop.size());
  for (const int v : loop) polygon.push_back(shadow(v));
  return polygon.size() >= 3 && CGAL::is_simple_2(polygon.begin(), polygon.end(), Kernel());
}

}  // namespace scanstation
