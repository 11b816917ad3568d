#include "reconstruct/smallest_enclosing_ball.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Min_sphere_of_points_d_traits_2.h>
#include <CGAL/Min_sphere_of_points_d_traits_3.h>
#include <CGAL/Min_sphere_of_spheres_d.h>

namespace scanstation {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
template <int D>
using Traits = std::conditional_t<D == 2, CGAL::Min_sphere_of_points_d_traits_2<Kernel, double, CGAL::Tag_true>,
                                  CGAL::Min_sphere_of_points_d_traits_3<Kernel, double, CGAL::Tag_true>>;

Kernel::Point_2 point(const Eigen::Matrix<double, Eigen::Dynamic, 2>& P, Eigen::Index i) { return {P(i, 0), P(i, 1)}; }
Kernel::Point_3 point(const Eigen::Matrix<double, Eigen::Dynamic, 3>& P, Eigen::Index i) {
  return {P(i, 0), P(i, 1), P(i, 2)};
}
}  // namespace

template <int D>
EnclosingBall<D> smallest_enclosing_ball(const Eigen::Matrix<double, Eigen::Dynamic, D>& P) {
  using Point = typename Traits<D>::Point;
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(P.rows()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) points.push_back(point(P, i));
  CGAL::Min_sphere_of_spheres_d<Traits<D>> ball(points.begin(), points.end());
  EnclosingBall<D> result;
  auto c = ball.center_cartesian_begin();
  for (int k = 0; k < D; ++k, ++c) result.center[k] = *c;
  result.radius = ball.radius();
  // The support points are copies; find the rows they came from.
  for (auto it = ball.support_begin(); it != ball.support_end(); ++it)
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      if (points[static_cast<std::size_t>(i)] == *it) {
        result.support.push_back(static_cast<int>(i));
        break;
      }
  return result;
}

template EnclosingBall<2> smallest_enclosing_ball<2>(const Eigen::Matrix<double, Eigen::Dynamic, 2>&);
template EnclosingBall<3> smallest_enclosing_ball<3>(const Eigen::Matrix<double, Eigen::Dynamic, 3>&);

}  // namespace scanstation
