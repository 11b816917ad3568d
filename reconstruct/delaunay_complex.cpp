#include "reconstruct/delaunay_complex.h"

#include "core/errors.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <string>
#include <utility>
#include <vector>

namespace scanstation {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

using Vb2 = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using Fb2 = CGAL::Triangulation_face_base_with_info_2<int, Kernel>;
using Delaunay2 = CGAL::Delaunay_triangulation_2<Kernel, CGAL::Triangulation_data_structure_2<Vb2, Fb2>>;

using Vb3 = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
using Cb3 = CGAL::Triangulation_cell_base_with_info_3<int, Kernel>;
using Delaunay3 = CGAL::Delaunay_triangulation_3<Kernel, CGAL::Triangulation_data_structure_3<Vb3, Cb3>>;

void require_points(Eigen::Index n, int needed, const char* shape) {
  if (n < needed)
    throw InvalidInput("need at least " + std::to_string(needed) + " distinct points for a closed " + shape +
                       ", got " + std::to_string(n));
}

// Inserts (point, index) pairs in spatial (Hilbert) order, each located from
// the previous vertex, recording the index on the vertex. Sorting the pairs
// themselves rather than indices into them keeps the sort cache-friendly:
// this is as fast as CGAL's plain range insertion, where the with-info range
// insertion is about 30% slower.
Delaunay2::Face_handle near(Delaunay2::Vertex_handle v) { return v == Delaunay2::Vertex_handle() ? Delaunay2::Face_handle() : v->face(); }
Delaunay3::Cell_handle near(Delaunay3::Vertex_handle v) { return v == Delaunay3::Vertex_handle() ? Delaunay3::Cell_handle() : v->cell(); }

template <typename Point>
using FirstOfPair = CGAL::First_of_pair_property_map<std::pair<Point, int>>;

template <typename Traits, typename Triangulation, typename Point>
void insert_in_spatial_order(Triangulation& dt, std::vector<std::pair<Point, int>>& input) {
  CGAL::spatial_sort(input.begin(), input.end(), Traits(FirstOfPair<Point>()));
  typename Triangulation::Vertex_handle hint;
  for (const auto& [point, index] : input) {
    const auto before = dt.number_of_vertices();
    hint = dt.insert(point, near(hint));
    if (dt.number_of_vertices() > before) hint->info() = index;  // a repeated point keeps its first index
  }
}

}  // namespace

DelaunayComplex<2> delaunay_complex(const Eigen::MatrixX2d& P) {
  require_points(P.rows(), 3, "polygon");
  std::vector<std::pair<Kernel::Point_2, int>> input;
  input.reserve(static_cast<std::size_t>(P.rows()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) input.emplace_back(Kernel::Point_2(P(i, 0), P(i, 1)), static_cast<int>(i));
  Delaunay2 dt;
  insert_in_spatial_order<CGAL::Spatial_sort_traits_adapter_2<Kernel, FirstOfPair<Kernel::Point_2>>>(dt, input);
  if (dt.dimension() < 2) throw InvalidInput("all points lie on one line: no polygon encloses them");

  DelaunayComplex<2> out;
  out.points = P;
  out.cells.resize(static_cast<Eigen::Index>(dt.number_of_faces()), 3);
  out.neighbors.resize(out.cells.rows(), 3);
  int id = 0;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) f->info() = id++;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
    for (int i = 0; i < 3; ++i) {
      out.cells(f->info(), i) = f->vertex(i)->info();
      const auto n = f->neighbor(i);
      out.neighbors(f->info(), i) = dt.is_infinite(n) ? -1 : n->info();
    }
  return out;
}

DelaunayComplex<3> delaunay_complex(const Eigen::MatrixX3d& P) {
  require_points(P.rows(), 4, "polyhedron");
  std::vector<std::pair<Kernel::Point_3, int>> input;
  input.reserve(static_cast<std::size_t>(P.rows()));
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    input.emplace_back(Kernel::Point_3(P(i, 0), P(i, 1), P(i, 2)), static_cast<int>(i));
  Delaunay3 dt;
  insert_in_spatial_order<CGAL::Spatial_sort_traits_adapter_3<Kernel, FirstOfPair<Kernel::Point_3>>>(dt, input);
  if (dt.dimension() < 3) throw InvalidInput("all points lie in one plane: no polyhedron encloses them");

  DelaunayComplex<3> out;
  out.points = P;
  out.cells.resize(static_cast<Eigen::Index>(dt.number_of_finite_cells()), 4);
  out.neighbors.resize(out.cells.rows(), 4);
  int id = 0;
  for (auto c : dt.finite_cell_handles()) c->info() = id++;
  for (auto c : dt.finite_cell_handles())
    for (int i = 0; i < 4; ++i) {
      out.cells(c->info(), i) = c->vertex(i)->info();
      const auto n = c->neighbor(i);
      out.neighbors(c->info(), i) = dt.is_infinite(n) ? -1 : n->info();
    }
  return out;
}

}  // namespace scanstation
