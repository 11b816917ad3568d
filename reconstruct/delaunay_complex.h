// The Delaunay triangulation as plain index arrays: the starting graph
// γ([-1,1],[0,1]) of constriction (thesis §5.1), which equals the Delaunay
// triangulation when no k+2 points are co-spherical.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <span>
#include <vector>

namespace scanstation {

/// D = 2 (triangles) or 3 (tetrahedra).
/// points     #P by D coordinates (distinct)
/// cells      #C by D+1 vertex indices of the finite Delaunay cells, positively
///            oriented (counter-clockwise in 2D; orientation(v0,v1,v2,v3) > 0 in 3D)
/// neighbors  #C by D+1: neighbors(c, i) is the cell across the face of c
///            opposite its vertex i, or −1 across the convex hull
/// Cells and neighbours are stored row by row: constriction reads a cell's
/// entries together and in no spatial order, one cache line where the
/// columns were three or four (in 3D its walks around edges read four
/// vertices of every cell they pass: constriction's stage 4–8% faster on
/// CGAL's armadillo, bunny00 and man, best of 11 alternating runs). So are
/// the points in 2D; in 3D they stay by column (a row-major copy inside
/// constriction changed nothing measurable).
template <int D>
struct DelaunayComplex {
  static constexpr int kPointOrder = D == 2 ? Eigen::RowMajor : Eigen::ColMajor;
  using Points = Eigen::Matrix<double, Eigen::Dynamic, D, kPointOrder>;
  using Cells = Eigen::Matrix<int, Eigen::Dynamic, D + 1, Eigen::RowMajor>;
  Points points;
  Cells cells;
  Cells neighbors;
};

/// 3D: the vertices of the face of a cell opposite its local vertex i,
/// counter-clockwise seen from outside the (positively oriented) cell.
inline constexpr int kFace3[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

/// 3D: walks the ring of cells around the edge (u, v) of cell c, each cell
/// joined to the next through a face holding the edge, and calls step(x, y)
/// for each cell x and the next one y (−1 beyond the convex hull) until it
/// returns false. Where the ring is open (at the hull, or at the rim of a
/// local complex) the walk goes both ways from c.
/// k       the local indices in c of its other two vertices
/// Returns false if step stopped the walk.
///
/// Each step is branch-free: cell y, entered through its face (u, v, stay),
/// holds one vertex new to the walk, the XOR of its four vertices and the
/// three known ones, and is left through the face opposite stay. The search
/// loops this replaces were a fifth of constriction's own instructions on
/// CGAL's armadillo.
template <typename Step>
bool walk_ring(const DelaunayComplex<3>& dt, int c, int u, int v, const int (&k)[2], Step&& step) {
  for (int direction = 0; direction < 2; ++direction) {
    int x = c, leave = k[direction], stay = dt.cells(c, k[1 - direction]);
    for (;;) {
      const int y = dt.neighbors(x, leave);
      if (!step(x, y)) return false;
      if (y < 0) break;          // open ring: the other way round
      if (y == c) return true;   // closed ring, all seen
      const int a = dt.cells(y, 0), b = dt.cells(y, 1), cc = dt.cells(y, 2), d = dt.cells(y, 3);
      leave = (b == stay) + 2 * (cc == stay) + 3 * (d == stay);
      stay = a ^ b ^ cc ^ d ^ u ^ v ^ stay;
      x = y;
    }
  }
  return true;
}

/// Builds the Delaunay triangulation with CGAL (exact predicates; points
/// inserted in spatial order). A repeated row is inserted once: the cells then
/// index one of its copies (in 2D its first occurrence; in 3D whichever came
/// first in that order), and the other copies appear in no cell (merge
/// duplicates first, or renumber the cells). Throws InvalidInput when fewer
/// than D+1 rows are given or all points lie on a line (2D) or a plane (3D):
/// then no closed boundary encloses them.
DelaunayComplex<2> delaunay_complex(const Eigen::MatrixX2d& P);
DelaunayComplex<3> delaunay_complex(const Eigen::MatrixX3d& P);

/// The Delaunay triangulation of the distinct rows of P, the duplicates found
/// on the way: CGAL's insertion meets a repeated point at the vertex already
/// there, so no separate pass over the points is needed. The points are
/// numbered in spatial order (CGAL's insertion order), so that cells close
/// together read points close together in memory.
/// first  (output) per point of the complex, the row of P it is (the first
///        occurrence of its value)
/// map    (output) #P entries: map[i] is the point of the complex equal to
///        P.row(i) (−0.0 and +0.0 count as equal); empty when no row
///        repeats another (then map is the inverse of first)
/// scale  a power of two the points are multiplied by (exactly) on the way
///        in, so that no scaled copy of P is made
/// Returns the complex of the points scale · P.row(first[k]) (cells index k).
/// Throws InvalidInput for fewer than 3 distinct points or all points on a
/// line.
DelaunayComplex<2> delaunay_complex(const Eigen::MatrixX2d& P, std::vector<Eigen::Index>& first,
                                    std::vector<Eigen::Index>& map, double scale = 1.0);

/// 3D: the complex with its points numbered in spatial order, as above, and
/// its cells by their last point in that order (neighbours in space are
/// mostly near in memory too).
/// rows  (output) per point of the complex, the row of P it is: one row per
///       distinct value (of a repeated row, whichever copy CGAL met first;
///       the others appear nowhere)
/// scale as in 2D
/// Returns the complex of the points scale · P.row(rows[k]) (cells index k).
DelaunayComplex<3> delaunay_complex(const Eigen::MatrixX3d& P, std::vector<Eigen::Index>& rows, double scale = 1.0);

/// The cells around each point of a complex, by a counting sort (linear):
/// those of v, in increasing cell order.
struct CellsAround {
  explicit CellsAround(const DelaunayComplex<2>& dt);
  explicit CellsAround(const DelaunayComplex<3>& dt);
  std::span<const int> operator[](std::size_t v) const {
    return {around.data() + start[v], start[v + 1] - start[v]};
  }
  std::vector<std::size_t> start;  // those of v: around[start[v] .. start[v + 1])
  std::vector<int> around;
};

}  // namespace scanstation
