#include "smoothing/fitted_normals.h"

#include "core/errors.h"
#include "smoothing/vertex_normals.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/property_map.h>
#include <Eigen/Eigenvalues>
#include <boost/iterator/counting_iterator.hpp>

#include <string>
#include <vector>

namespace scanstation {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using PointMap = CGAL::Pointer_property_map<Kernel::Point_3>::type;
using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, CGAL::Search_traits_3<Kernel>>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;

// cos 45°: the largest turn of a fitted normal from the face normals kept.
constexpr double kMostFromFaces = 0.70710678118654752;

}  // namespace

Eigen::MatrixX3d fitted_vertex_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, int neighbours) {
  if (neighbours < 3 || neighbours > V.rows())
    throw InvalidInput("fitted normals: the neighbour count must be between 3 and the " + std::to_string(V.rows()) +
                       " vertices, got " + std::to_string(neighbours));
  const Eigen::MatrixX3d side = vertex_normals(V, F, NormalWeighting::area);  // zero off the surface
  std::vector<Kernel::Point_3> points;
  points.reserve(static_cast<std::size_t>(V.rows()));
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    points.emplace_back(V(i, 0), V(i, 1), V(i, 2));
  const PointMap map = CGAL::make_property_map(points);
  const Search::Tree tree(boost::counting_iterator<std::size_t>(0), boost::counting_iterator<std::size_t>(points.size()),
                          Search::Tree::Splitter(), Traits(map));
  const Search::Distance distance(map);

  Eigen::MatrixX3d N = side;
  std::vector<Eigen::Index> near;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    if (side.row(i).isZero()) continue;
    // Only neighbours on the same side of the surface: across a thin wall
    // (a cup's rim, a plate) the nearest points may lie on the other face,
    // whose normals point the other way.
    near.clear();
    const Search search(tree, points[static_cast<std::size_t>(i)], static_cast<unsigned int>(neighbours), 0, true,
                        distance);
    for (const auto& [j, squared] : search)
      if (side.row(static_cast<Eigen::Index>(j)).dot(side.row(i)) > 0) near.push_back(static_cast<Eigen::Index>(j));
    if (near.size() < 3) continue;  // too few to fit a plane
    Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
    for (const Eigen::Index j : near) centre += V.row(j);
    centre /= static_cast<double>(near.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (const Eigen::Index j : near) {
      const Eigen::Vector3d d = (V.row(j) - centre).transpose();
      scatter += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> fit(scatter);
    // Neighbours on one line (or one point) hold no plane: the face normals stand.
    if (fit.info() != Eigen::Success || !(fit.eigenvalues()(1) > 1e-12 * fit.eigenvalues()(2))) continue;
    Eigen::Vector3d n = fit.eigenvectors().col(0);  // the smallest spread: the plane's normal
    if (n.dot(side.row(i).transpose()) < 0) n = -n;
    // A plane that turns more than 45° from the vertex's own faces does not
    // stand for them: a rim where a hull face closes space the scan never
    // saw (a bowl's lid over its unseen inside) or a sharp edge. The patches
    // over those faces would leave the vertex across them and fold out into
    // flaps (a scanned bowl's lid: 20 units off its triangles on an object
    // 92 across; 2.2 with this). The face normals stand there.
    if (n.dot(side.row(i).normalized().transpose()) < kMostFromFaces) continue;
    N.row(i) = n.transpose();
  }
  return N;
}

}  // namespace scanstation
