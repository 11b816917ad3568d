#include "smoothing/same_side_neighbours.h"

#include "smoothing/vertex_normals.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/property_map.h>
#include <boost/iterator/counting_iterator.hpp>

namespace scanstation {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using PointMap = CGAL::Pointer_property_map<Kernel::Point_3>::type;
using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, CGAL::Search_traits_3<Kernel>>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;

}  // namespace

struct SameSideNeighbours::Tree {
  explicit Tree(const Eigen::MatrixX3d& V) {
    points.reserve(static_cast<std::size_t>(V.rows()));
    for (Eigen::Index i = 0; i < V.rows(); ++i) points.emplace_back(V(i, 0), V(i, 1), V(i, 2));
    map = CGAL::make_property_map(points);
    tree.emplace(boost::counting_iterator<std::size_t>(0), boost::counting_iterator<std::size_t>(points.size()),
                 Search::Tree::Splitter(), Traits(map));
  }
  std::vector<Kernel::Point_3> points;
  PointMap map;
  std::optional<Search::Tree> tree;
};

SameSideNeighbours::SameSideNeighbours(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F)
    : side_(vertex_normals(V, F, NormalWeighting::area)), tree_(std::make_unique<Tree>(V)) {}

SameSideNeighbours::~SameSideNeighbours() = default;

void SameSideNeighbours::near(Eigen::Index v, int k, std::vector<Eigen::Index>& out) const {
  out.clear();
  if (side_.row(v).isZero()) return;
  const Search search(*tree_->tree, tree_->points[static_cast<std::size_t>(v)], static_cast<unsigned int>(k), 0, true,
                      Search::Distance(tree_->map));
  out.push_back(v);  // first, also where other vertices share its position
  for (const auto& [j, squared] : search) {
    const auto u = static_cast<Eigen::Index>(j);
    if (u != v && side_.row(u).dot(side_.row(v)) > 0) out.push_back(u);
  }
}

}  // namespace scanstation
