// A closed triangle surface under edit, with the exact geometric tests that
// keep it simple while constriction's later stages change it (augmentation
// carves, edge flips): which points lie in a tetrahedron, and whether new
// triangles meet the surface anywhere but in shared vertices and edges.
#pragma once

#include "reconstruct/cell_blocks.h"
#include "reconstruct/u64_map.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace scanstation {

/// std::nextafter(f, −∞) and std::nextafter(f, +∞) without the library
/// call: the box grid rounds six coordinates outwards per face filed, and
/// the calls were a third of a surface's filing.
inline float float_below(float f) {
  if (std::isnan(f) || f == -std::numeric_limits<float>::infinity()) return f;
  if (f == 0.0f) return -std::numeric_limits<float>::denorm_min();
  const auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0.0f ? bits - 1 : bits + 1);
}
inline float float_above(float f) { return -float_below(-f); }

// A loose multi-level grid over axis-aligned boxes, for "which points /
// triangles are near this region": each box lives on the finest level where
// it spans at most two cells per axis, so long triangles cost no more than
// small ones. Each cell keeps its boxes next to the ids, so a visit rejects
// the boxes that miss the region without touching the caller's data.
class BoxGrid {
 public:
  BoxGrid(const Eigen::AlignedBox3d& bounds, double cell) : origin_(bounds.min()), cell_(cell) {}

  /// An empty grid with the same cells.
  BoxGrid empty_like() const { return BoxGrid(Eigen::AlignedBox3d(origin_, origin_), cell_); }

  void insert(int id, const Eigen::AlignedBox3d& box) {
    const int l = level_of(box);
    const Eigen::Array3i i = index(l, box.min());
    Cells& cells = level(l);
    const Entry entry(box, id);
    Cell& cell = cells[key(i)];
    cell.entries.push_back(entry);
    cell.reach.extend(entry.box);
    cells.occupy(i);
  }
  void erase(int id, const Eigen::AlignedBox3d& box) {
    const int l = level_of(box);
    auto& v = level(l)[key(index(l, box.min()))].entries;
    v.erase(std::remove_if(v.begin(), v.end(), [id](const Entry& e) { return e.id == id; }), v.end());
  }
  /// Calls f(id) for every id whose box meets `region`. When f returns bool,
  /// false stops the visit; visit returns false then. f may also take the
  /// box as filed (rounded outwards to floats) after the id: f(id, box),
  /// returning bool.
  template <typename F>
  bool visit(const Eigen::AlignedBox3d& region, F&& f) const {
    const FloatBox query(region);
    const auto call = [&](const Entry& e) {
      if (!e.box.meets(query)) return true;
      if constexpr (std::is_invocable_v<F&, int, const Eigen::AlignedBox3d&>) {
        return static_cast<bool>(f(e.id, e.box.box()));
      } else if constexpr (std::is_same_v<std::invoke_result_t<F&, int>, bool>) {
        return static_cast<bool>(f(e.id));
      } else {
        f(e.id);
        return true;
      }
    };
    for (int l = 0; l < static_cast<int>(levels_.size()); ++l) {
      const auto& cells = levels_[static_cast<std::size_t>(l)];
      if (cells.empty()) continue;
      // A box is filed under the cell of its minimum corner and reaches at
      // most one cell size beyond it. The cells probed are those of the
      // region within the level's occupied cells: a region reaching a far
      // outlier spans millions of cells of the fine levels, and without the
      // clip every query there visited every face.
      Eigen::AlignedBox3d grown = region;
      grown.min().array() -= size(l);
      const Eigen::Array3i lo = index(l, grown.min()).max(cells.occupied_min()),
                           hi = index(l, grown.max()).min(cells.occupied_max());
      if ((lo > hi).any()) continue;
      const auto scan = [&](const Cell& cell) {
        if (!cell.reach.meets(query)) return true;
        for (const Entry& e : cell.entries)
          if (!call(e)) return false;
        return true;
      };
      if (((hi - lo).cast<double>() + 1.0).prod() > static_cast<double>(cells.size())) {
        for (const Cell& cell : cells.lists())
          if (!scan(cell)) return false;
      } else {
        const bool completed = for_cells(lo, hi, [&](std::uint64_t k) {
          const Cell* cell = cells.find(k);
          return !cell || scan(*cell);
        });
        if (!completed) return false;
      }
    }
    return true;
  }

 private:
  // A box in floats rounded outwards, so it holds the double box (a visit
  // may report a few more ids, never fewer): 24 bytes instead of 48, and
  // the grid is a good part of a surface's memory (one entry per face). A
  // query region is rounded the same way, so an entry meeting the region
  // meets it too.
  struct FloatBox {
    FloatBox() = default;
    explicit FloatBox(const Eigen::AlignedBox3d& box) {
      for (int k = 0; k < 3; ++k) {
        lo[k] = float_below(static_cast<float>(box.min()[k]));
        hi[k] = float_above(static_cast<float>(box.max()[k]));
      }
    }
    Eigen::AlignedBox3d box() const {
      return {Eigen::Vector3f(lo[0], lo[1], lo[2]).cast<double>(), Eigen::Vector3f(hi[0], hi[1], hi[2]).cast<double>()};
    }
    bool meets(const FloatBox& q) const {
      return (hi[0] >= q.lo[0]) & (hi[1] >= q.lo[1]) & (hi[2] >= q.lo[2]) & (lo[0] <= q.hi[0]) & (lo[1] <= q.hi[1]) &
             (lo[2] <= q.hi[2]);
    }
    void extend(const FloatBox& b) {
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], b.lo[k]);
        hi[k] = std::max(hi[k], b.hi[k]);
      }
    }
    float lo[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                   std::numeric_limits<float>::infinity()};
    float hi[3] = {-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                   -std::numeric_limits<float>::infinity()};
  };
  struct Entry {
    Entry(const Eigen::AlignedBox3d& b, int id) : box(b), id(id) {}
    FloatBox box;
    int id;
  };
  // One cell's entries and the box they reach (it grows with each insert
  // and never shrinks). A box is filed under the cell of its minimum
  // corner, so a query probes the cells up to one cell size below it; most
  // of those hold only boxes that stop short of it, told by this one test
  // instead of reading all their entries.
  struct Cell {
    FloatBox reach;
    std::vector<Entry> entries;
  };
  // The occupied cells of one level, by key. Queries probe many cells, most
  // of them empty, so the lookup is the grid's inner loop
  // (std::unordered_map's modulo and node chasing cost about a sixth of a
  // whole reconstruction on real meshes).
  class Cells {
   public:
    bool empty() const { return lists_.empty(); }
    std::size_t size() const { return lists_.size(); }
    const std::vector<Cell>& lists() const { return lists_; }
    const Cell* find(std::uint64_t k) const {
      const std::uint32_t* i = index_.find(k);
      return i ? &lists_[*i] : nullptr;
    }
    Cell& operator[](std::uint64_t k) {
      if (const std::uint32_t* i = index_.find(k)) return lists_[*i];
      index_[k] = static_cast<std::uint32_t>(lists_.size());
      return lists_.emplace_back();
    }
    // The cell indices ever filed under, as a box (it never shrinks).
    void occupy(const Eigen::Array3i& i) {
      low_ = low_.min(i);
      high_ = high_.max(i);
    }
    const Eigen::Array3i& occupied_min() const { return low_; }
    const Eigen::Array3i& occupied_max() const { return high_; }

   private:
    U64Map<std::uint32_t> index_;  // list of each cell key
    std::vector<Cell> lists_;
    Eigen::Array3i low_ = Eigen::Array3i::Constant(std::numeric_limits<int>::max());
    Eigen::Array3i high_ = Eigen::Array3i::Constant(std::numeric_limits<int>::min());
  };
  double size(int l) const { return cell_ * static_cast<double>(std::uint64_t{1} << l); }
  Cells& level(int l) {
    if (static_cast<int>(levels_.size()) <= l) levels_.resize(static_cast<std::size_t>(l) + 1);
    return levels_[static_cast<std::size_t>(l)];
  }
  int level_of(const Eigen::AlignedBox3d& box) const {
    const double extent = (box.max() - box.min()).maxCoeff();
    int l = 0;
    while (l < 40 && extent > size(l)) ++l;
    return l;
  }
  Eigen::Array3i index(int l, const Eigen::Vector3d& x) const {  // clamped: a far corner stays an int
    return ((x - origin_) / size(l)).array().floor().max(-1e9).min(1e9).cast<int>();
  }
  static std::uint64_t key(const Eigen::Array3i& i) {
    return (static_cast<std::uint64_t>(i.x() & 0x1FFFFF) << 42) | (static_cast<std::uint64_t>(i.y() & 0x1FFFFF) << 21) |
           static_cast<std::uint64_t>(i.z() & 0x1FFFFF);
  }
  template <typename F>
  static bool for_cells(const Eigen::Array3i& lo, const Eigen::Array3i& hi, F&& f) {
    for (int x = lo.x(); x <= hi.x(); ++x)
      for (int y = lo.y(); y <= hi.y(); ++y)
        for (int z = lo.z(); z <= hi.z(); ++z)
          if (!f(key(Eigen::Array3i(x, y, z)))) return false;
    return true;
  }
  Eigen::Vector3d origin_;
  double cell_;
  std::vector<Cells> levels_;
};

/// An empty grid over the bounding box of P for the triangles `faces` (a
/// closed surface through P), some 32 triangles per cell (the one
/// BoundarySurface files its faces in).
BoxGrid surface_grid(const Eigen::MatrixX3d& P, const Eigen::MatrixX3i& faces);

// A static k-d tree over points, for "which points lie in this box": the
// points never move while a surface is edited, and on non-uniform samplings
// (dense scans next to wide gaps) a query box of a long triangle or a wide
// circumball spans thousands of grid cells, most of them empty, where the
// tree visits only the few nodes the box meets.
class PointTree {
 public:
  explicit PointTree(const Eigen::MatrixX3d& P);
  /// Calls f(id, position) for every point in the closed `region`; f
  /// returns false to stop early, and visit returns false then. The
  /// position comes from the tree's own copy, stored leaf by leaf: reading
  /// it from the caller's (column-major) matrix costs three scattered
  /// loads per point, and wide queries visit thousands of points.
  template <typename F>
  bool visit(const Eigen::AlignedBox3d& region, F&& f) const {
    return walk([&](const Eigen::AlignedBox3d& box) { return region.intersects(box); },
                [&](const Eigen::Vector3d& p) { return region.contains(p); }, [](int, int) { return true; }, f);
  }

  /// The same for the points within distance r of c (a superset: the ball
  /// is closed and its test in floating point), visiting the nodes nearest
  /// c first, so that a search stopped by the first point of some kind near
  /// the centre ends early.
  template <typename F>
  bool visit_ball(const Eigen::Vector3d& c, double r, F&& f) const {
    const double reach = r * r * (1.0 + 1e-12);
    const auto distance = [&](int node) { return nodes_[static_cast<std::size_t>(node)].box.squaredExteriorDistance(c); };
    return walk([&](const Eigen::AlignedBox3d& box) { return box.squaredExteriorDistance(c) <= reach; },
                [&](const Eigen::Vector3d& p) { return (p - c).squaredNorm() <= reach; },
                [&](int a, int b) { return distance(a) <= distance(b); }, f);
  }

 private:
  static constexpr int kLeaf = 8;
  struct Node {
    Eigen::AlignedBox3d box;
    int begin = 0, end = 0;
  };
  // Depth first over the nodes whose box `reaches` accepts, child a before
  // child b when first(a, b); f(id, position) for the points `holds`
  // accepts, until f returns false.
  template <typename Reaches, typename Holds, typename First, typename F>
  bool walk(Reaches&& reaches, Holds&& holds, First&& first, F&& f) const {
    if (items_.empty()) return true;
    int stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const int node = stack[--top];
      const Node& n = nodes_[static_cast<std::size_t>(node)];
      if (!reaches(n.box)) continue;
      if (n.end - n.begin <= kLeaf) {
        for (int k = n.begin; k < n.end; ++k)
          if (const Item& item = items_[static_cast<std::size_t>(k)];
              holds(item.position) && !f(item.id, item.position))
            return false;
        continue;
      }
      const int a = 2 * node + 1, b = 2 * node + 2;
      const bool a_first = first(a, b);  // the one pushed last is visited first
      stack[top++] = a_first ? b : a;
      stack[top++] = a_first ? a : b;
    }
    return true;
  }
  struct Item {
    Eigen::Vector3d position;
    int id;
  };
  static constexpr int kParallelPoints = 8192;
  void build(int node, int begin, int end);
  std::vector<Item> items_;                 // the points, grouped by leaf
  std::vector<Node> nodes_;                 // implicit binary tree: children 2i+1, 2i+2
};

/// An edge lo < hi of a closed surface and the mark select_edges gave it.
struct MarkedEdge {
  int lo, hi;
  unsigned mark;
};

/// The edges lo < hi shared by a face (lo, hi, c) and a face (hi, lo, d) of
/// the closed, oriented surface F over n points for which select(lo, hi, c,
/// d) returns a nonzero mark, with their marks, in order of lo, then hi.
/// Linear time: half-edges bucketed by their lower vertex by counting sort,
/// then paired within each small bucket (a million-face surface has six
/// million half-edges, too many for a comparison sort to be cheap).
/// Unpaired half-edges are skipped. The buckets are paired and judged on all
/// cores, by blocks of lower vertices (select must be safe to call
/// concurrently): on CGAL's real meshes the flips' and unfolding's two
/// passes had been about a thirtieth of a reconstruction, with the other
/// core idle.
template <typename Select>
std::vector<MarkedEdge> select_edges(Eigen::Index n, const Eigen::MatrixX3i& F, Select&& select) {
  struct Half {
    int hi, opposite;
    bool forward;
  };
  std::vector<std::size_t> start(static_cast<std::size_t>(n) + 1, 0);
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) ++start[static_cast<std::size_t>(std::min(F(t, k), F(t, (k + 1) % 3))) + 1];
  for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<Half> halves(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int u = F(t, k), v = F(t, (k + 1) % 3);
      halves[fill[static_cast<std::size_t>(std::min(u, v))]++] = {std::max(u, v), F(t, (k + 2) % 3), u < v};
    }
  constexpr std::size_t kPointsPerBlock = 4096;
  const auto points = static_cast<std::size_t>(n);
  std::vector<std::vector<MarkedEdge>> found((points + kPointsPerBlock - 1) / kPointsPerBlock);
  for_each_block(found.size(), [&](std::size_t b) {
    for (std::size_t lo = b * kPointsPerBlock; lo < std::min(points, (b + 1) * kPointsPerBlock); ++lo) {
      const auto first = halves.begin() + static_cast<std::ptrdiff_t>(start[lo]);
      const auto last = halves.begin() + static_cast<std::ptrdiff_t>(start[lo + 1]);
      std::sort(first, last, [](const Half& x, const Half& y) { return std::tie(x.hi, x.forward) < std::tie(y.hi, y.forward); });
      for (auto x = first; x != last && x + 1 != last; ++x) {
        const auto y = x + 1;
        // y runs lo → hi (forward sorts last): its face is (lo, hi, y->opposite).
        if (x->hi != y->hi) continue;
        if (const unsigned mark = select(static_cast<int>(lo), x->hi, y->opposite, x->opposite))
          found[b].push_back({static_cast<int>(lo), x->hi, mark});
      }
    }
  });
  std::vector<MarkedEdge> out;
  for (const std::vector<MarkedEdge>& block : found) out.insert(out.end(), block.begin(), block.end());
  return out;
}

/// faces are counter-clockwise seen from outside; ids stay valid (a removed
/// face is marked dead, new faces get new ids).
class BoundarySurface {
 public:
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Triangle = std::array<int, 3>;

  /// P #P by 3 positions; boundary #F by 3 faces; points optional: a tree
  /// over P built beforehand (else built on the first point query)
  BoundarySurface(const Eigen::MatrixX3d& P, const Eigen::MatrixX3i& boundary,
                  std::shared_ptr<const PointTree> points = nullptr);

  int add_face(const Triangle& t);
  void remove_face(int id);

  const Triangle& face(int id) const { return faces_[static_cast<std::size_t>(id)]; }
  bool alive(int id) const { return alive_[static_cast<std::size_t>(id)] != 0; }
  std::size_t face_slots() const { return faces_.size(); }
  /// The faces it was built with: ids [0, built_faces()) are the rows of
  /// `boundary`, later ids come from edits.
  std::size_t built_faces() const { return built_faces_; }
  /// The alive faces' count.
  std::size_t face_count() const { return alive_faces_; }
  /// Ids of faces that used vertex v at some point (check alive()).
  const std::vector<int>& faces_at(int v) const { return faces_at_[static_cast<std::size_t>(v)]; }
  bool on_boundary(int v) const { return on_boundary_[static_cast<std::size_t>(v)] != 0; }
  /// An alive face holds the edge (u, v).
  bool has_edge(int u, int v) const;
  /// The alive face holding the directed edge a → b and its third vertex;
  /// (-1, -1) if there is none.
  std::pair<int, int> face_with(int a, int b) const;

  Eigen::Vector3d point(int i) const { return P_.row(i).transpose(); }
  const Kernel::Point_3& exact(int i) const { return cgal_[static_cast<std::size_t>(i)]; }
  Eigen::AlignedBox3d box(std::initializer_list<int> ids) const;

  /// Exact: the triangles meet anywhere but in the vertices/edges they share.
  bool improper(const Triangle& s, const Triangle& t) const;
  /// Exact: some point other than a, b, c, d lies in the closed tetrahedron
  /// (a, b, c, d), which must not be flat.
  bool point_in_tetrahedron(int a, int b, int c, int d) const;
  /// Exact: some alive face other than those in `except` meets one of
  /// `fresh` improperly.
  bool meets_surface(const std::vector<Triangle>& fresh, std::initializer_list<int> except) const {
    return meets_faces(fresh, except, faces_grid_);
  }
  /// The same among the faces filed in `faces` (ids of this surface's faces
  /// by their boxes, dead ones allowed): where only some faces can cut the
  /// fresh ones (see flip_boundary).
  bool meets_faces(const std::vector<Triangle>& fresh, std::initializer_list<int> except, const BoxGrid& faces) const;
  /// An empty grid with the cells of the one the faces are filed in, for a
  /// subset of them (see meets_faces).
  BoxGrid empty_grid() const { return faces_grid_.empty_like(); }
  /// f(q, position of q) for the points q within distance r of c (and
  /// perhaps a few on its rim), nearest first by tree node; f may return
  /// false to stop early.
  template <typename F>
  bool points_in_ball(const Eigen::Vector3d& c, double r, F&& f) const { return points().visit_ball(c, r, f); }

  /// The alive faces.
  Eigen::MatrixX3i boundary() const;

 private:
  const Eigen::MatrixX3d& P_;
  std::vector<Kernel::Point_3> cgal_;
  // Given, or built on the first point query (unfolding asks none); one
  // surface serves one thread.
  const PointTree& points() const {
    if (!points_) points_ = std::make_shared<const PointTree>(P_);
    return *points_;
  }
  mutable std::shared_ptr<const PointTree> points_;
  BoxGrid faces_grid_;
  std::vector<Triangle> faces_;
  std::vector<char> alive_;
  std::size_t alive_faces_ = 0;
  std::size_t built_faces_ = 0;
  std::vector<std::vector<int>> faces_at_;
  std::vector<char> on_boundary_;
};

}  // namespace scanstation
