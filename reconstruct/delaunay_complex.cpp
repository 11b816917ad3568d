#include "reconstruct/delaunay_complex.h"

#include "core/errors.h"
#include "core/predicates.h"
#include "reconstruct/cell_blocks.h"
#include "reconstruct/spatial_order.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <numeric>
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

// Inserts (point, index) pairs in spatial order (randomized Hilbert order,
// BRIO: a plain Hilbert order is about 10× slower on points along a curve;
// brio_hilbert_sort), each located from the previous vertex, recording the
// index on the vertex. Sorting the pairs themselves rather than indices into
// them keeps the insertion's reads in order: CGAL's with-info range
// insertion is about 30% slower than its plain one. A repeated point
// leaves the triangulation as it was; CGAL returns the vertex already there,
// which keeps its index, and repeat(index, vertex) hears of it.
Delaunay2::Face_handle near(Delaunay2::Vertex_handle v) { return v == Delaunay2::Vertex_handle() ? Delaunay2::Face_handle() : v->face(); }
Delaunay3::Cell_handle near(Delaunay3::Vertex_handle v) { return v == Delaunay3::Vertex_handle() ? Delaunay3::Cell_handle() : v->cell(); }

template <typename Triangulation, typename Point, typename Repeat>
void insert_in_spatial_order(Triangulation& dt, std::vector<std::pair<Point, int>>& input, Repeat&& repeat) {
  brio_hilbert_sort(input);
  typename Triangulation::Vertex_handle hint;
  for (const auto& [point, index] : input) {
    const auto before = dt.number_of_vertices();
    hint = dt.insert(point, near(hint));
    if (dt.number_of_vertices() > before) {
      hint->info() = index;
    } else {
      repeat(index, hint);
    }
  }
}

// Numbers the finite cells (faces in 2D) in CGAL's storage order, infinite
// ones −1 (so a neighbour's number needs no test of its vertices), then
// copies their points' and neighbours' numbers into `out`: one pass for the
// numbers (a neighbour may come later in that order), then the copy by
// blocks (cell_blocks.h), each from the iterator the first pass kept at its
// start (at 1M points in 2D the copy was a twentieth of the reconstruction,
// with the other core idle).
template <int D, typename Triangulation, typename Iterator>
void copy_cells(const Triangulation& dt, Iterator begin, Iterator end, DelaunayComplex<D>& out) {
  std::vector<Iterator> block_start;
  int id = 0;
  for (Iterator c = begin; c != end; ++c) {
    if (dt.is_infinite(c)) {
      c->info() = -1;
      continue;
    }
    if (static_cast<std::size_t>(id) % kCellBlock == 0) block_start.push_back(c);
    c->info() = id++;
  }
  block_start.push_back(end);
  out.cells.resize(id, D + 1);
  out.neighbors.resize(id, D + 1);
  for_each_block(block_start.size() - 1, [&](std::size_t b) {
    for (Iterator c = block_start[b]; c != block_start[b + 1]; ++c) {
      const int cell = c->info();
      if (cell < 0) continue;
      for (int i = 0; i <= D; ++i) {
        out.cells(cell, i) = c->vertex(i)->info();
        out.neighbors(cell, i) = c->neighbor(i)->info();
      }
    }
  });
}

// Renumbers the cells of a 3D complex by their last point in insertion
// order (a counting sort, stable), and their neighbours with them. CGAL's
// storage order reuses the slots of cells deleted long before, so cells
// next to each other in space lie all over the arrays; constriction, which
// pops cells in key order and then reads their neighbours' rows and states,
// waits for memory at nearly every step. Three quarters of the points are
// in the last round of the insertion order, along one Hilbert curve, and
// nearly every cell has one of them: in this order neighbours are mostly
// near in memory too (constriction on CGAL's 26 closed genus-0 meshes
// 0.80–0.86× → 0.72–0.74× of CGAL's Delaunay time, alternating runs). The
// rows are permuted on both cores, each block of old rows written to its
// new places.
void order_cells_by_last_point(DelaunayComplex<3>& out) {
  const auto cells = static_cast<std::size_t>(out.cells.rows());
  std::vector<int> slot(cells);  // first each cell's last point, then its new row
  std::vector<int> to(static_cast<std::size_t>(out.points.rows()) + 1, 0);  // first the counts, then the rows
  for (std::size_t c = 0; c < cells; ++c) {
    slot[c] = out.cells.row(static_cast<Eigen::Index>(c)).maxCoeff();
    ++to[static_cast<std::size_t>(slot[c]) + 1];
  }
  std::partial_sum(to.begin(), to.end(), to.begin());
  for (int& s : slot) s = to[static_cast<std::size_t>(s)]++;
  DelaunayComplex<3>::Cells ordered(out.cells.rows(), 4), neighbors(out.cells.rows(), 4);
  const std::size_t blocks = (cells + kCellBlock - 1) / kCellBlock;
  for_each_block(blocks, [&](std::size_t b) {
    for (std::size_t c = b * kCellBlock; c < std::min(cells, (b + 1) * kCellBlock); ++c) {
      const int row = slot[c];
      for (int i = 0; i < 4; ++i) {
        ordered(row, i) = out.cells(static_cast<Eigen::Index>(c), i);
        const int n = out.neighbors(static_cast<Eigen::Index>(c), i);
        neighbors(row, i) = n < 0 ? n : slot[static_cast<std::size_t>(n)];
      }
    }
  });
  out.cells = std::move(ordered);
  out.neighbors = std::move(neighbors);
}

using Repeats2 = std::vector<std::pair<int, Delaunay2::Vertex_handle>>;

// Numbers the distinct points as unique_points does (first occurrences in
// input order) from what the insertion saw, when some rows were repeated:
// each vertex holds the row that created it, `repeats` the other rows and
// their vertices. Vertex infos become indices into `first`.
void number_distinct(Delaunay2& dt, Repeats2& repeats, Eigen::Index rows, std::vector<Eigen::Index>& first,
                     std::vector<Eigen::Index>& map) {
  // The spatial order may meet a later copy first: the smallest row of each
  // vertex's copies stands for it (a running minimum, the rows swapped out
  // stay in `repeats`).
  for (auto& [row, v] : repeats)
    if (row < v->info()) std::swap(row, v->info());
  std::vector<char> distinct(static_cast<std::size_t>(rows), 0);
  for (const auto v : dt.finite_vertex_handles()) distinct[static_cast<std::size_t>(v->info())] = 1;
  first.clear();
  map.assign(static_cast<std::size_t>(rows), -1);
  for (Eigen::Index i = 0; i < rows; ++i)
    if (distinct[static_cast<std::size_t>(i)]) {
      map[static_cast<std::size_t>(i)] = static_cast<Eigen::Index>(first.size());
      first.push_back(i);
    }
  for (const auto& [row, v] : repeats) map[static_cast<std::size_t>(row)] = map[static_cast<std::size_t>(v->info())];
  for (const auto v : dt.finite_vertex_handles()) v->info() = static_cast<int>(map[static_cast<std::size_t>(v->info())]);
}

}  // namespace

DelaunayComplex<2> delaunay_complex(const Eigen::MatrixX2d& P, std::vector<Eigen::Index>& first,
                                    std::vector<Eigen::Index>& map, double scale) {
  // Points on one line are told before CGAL's triangulation, which walks
  // along the line for each of them (see all_collinear).
  if (const Eigen::MatrixX2d scaled = P * scale; all_collinear(scaled)) {
    std::vector<std::pair<double, double>> distinct;
    for (Eigen::Index i = 0; i < scaled.rows(); ++i) distinct.emplace_back(scaled(i, 0), scaled(i, 1));
    std::sort(distinct.begin(), distinct.end());
    require_points(std::unique(distinct.begin(), distinct.end()) - distinct.begin(), 3, "polygon");
    throw InvalidInput("all points lie on one line: no polygon encloses them");
  }
  Repeats2 repeats;
  Delaunay2 dt;
  {
    std::vector<std::pair<Kernel::Point_2, int>> input;
    input.reserve(static_cast<std::size_t>(P.rows()));
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      input.emplace_back(Kernel::Point_2(P(i, 0) * scale, P(i, 1) * scale), static_cast<int>(i));
    insert_in_spatial_order(dt, input, [&](int row, Delaunay2::Vertex_handle v) { repeats.emplace_back(row, v); });
  }
  const Eigen::Index distinct = P.rows() - static_cast<Eigen::Index>(repeats.size());
  require_points(distinct, 3, "polygon");
  if (dt.dimension() < 2) throw InvalidInput("all points lie on one line: no polygon encloses them");

  // The points renumbered in CGAL's vertex storage order, which is the
  // spatial insertion order: constriction then reads the points of nearby
  // cells from nearby memory (in input order they are scattered over the
  // whole array when the input is unordered). Coordinates are bit for bit
  // those of the first occurrence. No array is filled that is not needed
  // (map, when no row repeats): on a 1M-point input each fresh 8 MB costs
  // about 20 ms in page faults alone on the machines measured, and map's
  // writes go all over it.
  DelaunayComplex<2> out;
  out.points.resize(distinct, 2);
  std::vector<Eigen::Index> spatial_first(static_cast<std::size_t>(distinct));
  int k = 0;
  if (repeats.empty()) {  // every row is a vertex, holding its row; map stays empty
    map.clear();
    for (const auto v : dt.finite_vertex_handles()) {
      spatial_first[static_cast<std::size_t>(k)] = v->info();
      out.points(k, 0) = v->point().x();
      out.points(k, 1) = v->point().y();
      v->info() = k++;
    }
  } else {
    number_distinct(dt, repeats, P.rows(), first, map);
    std::vector<Eigen::Index> renumbered(first.size());
    for (const auto v : dt.finite_vertex_handles()) {
      const auto old = static_cast<std::size_t>(v->info());
      spatial_first[static_cast<std::size_t>(k)] = first[old];
      renumbered[old] = k;
      // From the first occurrence, not the vertex: the copy inserted first
      // may differ in the sign of a zero.
      out.points.row(k) = P.row(first[old]) * scale;
      v->info() = k++;
    }
    for (Eigen::Index& m : map) m = renumbered[static_cast<std::size_t>(m)];
  }
  first = std::move(spatial_first);

  copy_cells(dt, dt.all_faces_begin(), dt.all_faces_end(), out);
  return out;
}

DelaunayComplex<2> delaunay_complex(const Eigen::MatrixX2d& P) {
  std::vector<Eigen::Index> first, map;
  DelaunayComplex<2> out = delaunay_complex(P, first, map);
  for (Eigen::Index c = 0; c < out.cells.rows(); ++c)  // back to rows of P
    for (int i = 0; i < 3; ++i) out.cells(c, i) = static_cast<int>(first[static_cast<std::size_t>(out.cells(c, i))]);
  out.points = P;
  return out;
}

DelaunayComplex<3> delaunay_complex(const Eigen::MatrixX3d& P, std::vector<Eigen::Index>& rows, double scale) {
  require_points(P.rows(), 4, "polyhedron");
  DelaunayComplex<3> out;
  {
    std::vector<std::pair<Kernel::Point_3, int>> input;
    input.reserve(static_cast<std::size_t>(P.rows()));
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      input.emplace_back(Kernel::Point_3(P(i, 0) * scale, P(i, 1) * scale, P(i, 2) * scale), static_cast<int>(i));
    Delaunay3 dt;
    insert_in_spatial_order(dt, input, [](int, Delaunay3::Vertex_handle) {});
    std::vector<std::pair<Kernel::Point_3, int>>().swap(input);  // the copy below is the memory peak
    if (dt.dimension() < 3)
      throw InvalidInput(dt.dimension() < 2 ? std::string("all points lie on one line: no polyhedron encloses them")
                                            : std::string("all points lie in one plane: no polyhedron encloses them (give "
                                                          "them with two coordinates, x y, for a closed polygon)"));

    // Points in CGAL's vertex storage order (see the 2D version).
    out.points.resize(static_cast<Eigen::Index>(dt.number_of_vertices()), 3);
    rows.resize(dt.number_of_vertices());
    int k = 0;
    for (const auto v : dt.finite_vertex_handles()) {
      rows[static_cast<std::size_t>(k)] = v->info();
      out.points.row(k) = P.row(v->info()) * scale;
      v->info() = k++;
    }
    copy_cells(dt, dt.all_cells_begin(), dt.all_cells_end(), out);
  }
  order_cells_by_last_point(out);  // with CGAL's triangulation freed: the new rows take its memory
  return out;
}

DelaunayComplex<3> delaunay_complex(const Eigen::MatrixX3d& P) {
  std::vector<Eigen::Index> rows;
  DelaunayComplex<3> out = delaunay_complex(P, rows);
  for (Eigen::Index c = 0; c < out.cells.rows(); ++c)  // back to rows of P
    for (int i = 0; i < 4; ++i) out.cells(c, i) = static_cast<int>(rows[static_cast<std::size_t>(out.cells(c, i))]);
  out.points = P;
  return out;
}

namespace {
template <int D>
void index_cells_around(const DelaunayComplex<D>& dt, std::vector<std::size_t>& start, std::vector<int>& around) {
  const auto points = static_cast<std::size_t>(dt.points.rows());
  start.assign(points + 1, 0);
  for (Eigen::Index c = 0; c < dt.cells.rows(); ++c)
    for (int i = 0; i <= D; ++i) ++start[static_cast<std::size_t>(dt.cells(c, i)) + 1];
  for (std::size_t v = 0; v < points; ++v) start[v + 1] += start[v];
  around.resize(start[points]);
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (Eigen::Index c = 0; c < dt.cells.rows(); ++c)
    for (int i = 0; i <= D; ++i) around[fill[static_cast<std::size_t>(dt.cells(c, i))]++] = static_cast<int>(c);
}
}  // namespace

CellsAround::CellsAround(const DelaunayComplex<2>& dt) { index_cells_around(dt, start, around); }
CellsAround::CellsAround(const DelaunayComplex<3>& dt) { index_cells_around(dt, start, around); }

}  // namespace scanstation
