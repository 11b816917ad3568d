#include "core/predicates.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace scanstation {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
Kernel::Point_2 cgal(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }
Kernel::Point_3 cgal(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

int orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return static_cast<int>(CGAL::orientation(cgal(a), cgal(b), cgal(c)));
}

int orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                const Eigen::Vector3d& d) {
  return static_cast<int>(CGAL::orientation(cgal(a), cgal(b), cgal(c), cgal(d)));
}

int side_of_oriented_circle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                            const Eigen::Vector2d& d) {
  return static_cast<int>(CGAL::side_of_oriented_circle(cgal(a), cgal(b), cgal(c), cgal(d)));
}

int side_of_oriented_sphere(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                            const Eigen::Vector3d& d, const Eigen::Vector3d& e) {
  return static_cast<int>(CGAL::side_of_oriented_sphere(cgal(a), cgal(b), cgal(c), cgal(d), cgal(e)));
}

bool collinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return CGAL::collinear(cgal(a), cgal(b), cgal(c));
}

bool all_collinear(const Eigen::MatrixX2d& V) {
  const auto p = [&](Eigen::Index i) { return cgal(Eigen::Vector2d(V.row(i).transpose())); };
  Eigen::Index b = 1;
  while (b < V.rows() && V.row(b) == V.row(0)) ++b;
  for (Eigen::Index c = b + 1; c < V.rows(); ++c)
    if (!CGAL::collinear(p(0), p(b), p(c))) return false;
  return true;
}

bool all_coplanar(const Eigen::MatrixX3d& V) {
  const auto p = [&](Eigen::Index i) { return cgal(Eigen::Vector3d(V.row(i).transpose())); };
  Eigen::Index b = 1;
  while (b < V.rows() && V.row(b) == V.row(0)) ++b;
  Eigen::Index c = b + 1;
  while (c < V.rows() && CGAL::collinear(p(0), p(b), p(c))) ++c;
  for (Eigen::Index d = c + 1; d < V.rows(); ++d)
    if (CGAL::orientation(p(0), p(b), p(c), p(d)) != CGAL::COPLANAR) return false;
  return true;
}

}  // namespace scanstation
