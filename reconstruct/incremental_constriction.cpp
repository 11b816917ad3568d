#include "reconstruct/incremental_constriction.h"

#include "core/errors.h"
#include "reconstruct/gamma_indicator.h"
#include "reconstruct/line_of_sight.h"
#include "reconstruct/surface_link.h"
#include "reconstruct/u64_map.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/spatial_sort.h>
#include <CGAL/property_map.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iterator>
#include <numeric>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace scanstation {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// A cell created by insertion starts kept: the cavity of the new points is
// filled, as the convex hull is at the start of Algorithm 5.1, and then
// constricted again. `local` numbers the cell in the complex of one repair.
struct CellInfo {
  int local = -1;
  unsigned visit = 0;   // the walk that last reached the cell (State::star, State::joinable)
  unsigned filled = 0;  // the batch that filled the cell (made it, kept, to be re-decided); 0: none
  char kept = 1;
  // The γ-guide's decisions on the cell's faces so far, each kept while the
  // neighbour across the face lives (insert_in_zone forgets it where the
  // neighbour changes). Most of a scan-order batch's region was re-decided
  // in the batch before.
  GuideMemo guides;
};
// A vertex holds its point's index (info) and the last conflict zone that
// listed it (State::zone_points): marked in the vertex, which the
// insertion has at hand, not in an array by index, which missed the cache.
template <typename Base = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>>
struct ZoneVertex : Base {
  template <typename Tds>
  struct Rebind_TDS {
    using Other = ZoneVertex<typename Base::template Rebind_TDS<Tds>::Other>;
  };
  using Base::Base;
  unsigned zone = 0;
};
using Vb = ZoneVertex<>;
using Cb = CGAL::Triangulation_cell_base_with_info_3<CellInfo, Kernel>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, CGAL::Triangulation_data_structure_3<Vb, Cb>>;
using Cell = Delaunay::Cell_handle;
using Vertex = Delaunay::Vertex_handle;
using Indexed = std::pair<Kernel::Point_3, int>;
using SortTraits = CGAL::Spatial_sort_traits_adapter_3<Kernel, CGAL::First_of_pair_property_map<Indexed>>;

// How far a repair may widen: rounds of filling where the fill pinched the
// boundary; rings of kept cells released when the local constriction locks
// (one: the locks measured at 100k points in scan order were one or two new
// points that a second ring did not bring on either, and the second ring
// changed no recall on the 14 meshes of docs/design.md).
constexpr int kFillRounds = 200;
constexpr int kUnfreezeRings = 1;
// Layers of cells sharing a face with a scan front's margin rings, re-opened
// after the rings: a thinner skin than a third ring of whole stars (measured
// in docs/design.md, incremental constriction).
constexpr int kSkinLayers = 2;
// The longest crossing curve a new point is joined over (joinable): a
// longer one is a degenerate zone (many co-spherical points) and re-decided.
constexpr std::size_t kMaxJoinCycle = 64;

// The Euler characteristic of a closed triangulated 2-manifold is V − E + F
// = Σ_v (1 − f(v)/6), f(v) the triangles at v (E = 3F/2): six times a
// vertex's share, 0 for a point off the boundary.
int euler_share(int f) { return f > 0 ? 6 - f : 0; }

// The link of a boundary vertex (reconstruct/surface_link.h), its ends as
// vertex handles, compared without reading the vertices.
using LinkEdge = std::array<Vertex, 2>;

// The complex of one repair: first the cells to re-decide, then the cells
// around them (kept ones frozen, removed ones as the outside they are).
struct LocalComplex {
  DelaunayComplex<3> dt;
  ConstrictionStart start;
  std::vector<Cell> cells;
  std::vector<Vertex> vertices;
  std::vector<GuideMemo> guides;  // of the cells
  std::size_t region = 0;         // cells [0, region) are re-decided
  std::size_t core_vertices = 0;  // vertices [0, core_vertices) are those of the region cells
};

}  // namespace

struct IncrementalConstriction::State {
  ReconstructionOptions options;
  ConstrictionOptions constriction;
  int margin = 2;
  double local_share = 0.25;
  Delaunay dt;
  std::vector<Eigen::Vector3d> points;  // distinct points, in the order received
  std::vector<Eigen::Index> source;     // their rows in the stream of all batches
  std::vector<int> faces_at;            // f(v): boundary triangles at each point
  Eigen::Index corners = 0;             // Σ f(v): three per boundary triangle
  std::vector<char> pending;            // points constriction could not reach
  std::vector<Eigen::Vector3d> viewpoints;  // of the batches that gave one
  std::vector<int> viewpoint_of;        // per point: its batch's entry in viewpoints, else −1
  int batch_viewpoint = -1;             // of the batch being inserted
  std::vector<int> local_vertex;        // scratch: a point's number in a LocalComplex, else −1
  std::vector<int> f_now;               // scratch: f(v) while a fill is checked, else −1
  std::vector<char> pinched_now;        // scratch: the fill pinches the boundary at v
  std::vector<int> fill_vertex;         // scratch: a point's number in FillParts, else −1
  // scratch, for one repair: every finite cell around the point is in the
  // fill, so its boundary triangles are its convex hull triangles (a disk:
  // not pinched), inner[v] of them, and its star is in its part's local
  // complex; −1 otherwise
  std::vector<int> inner;
  std::vector<int> inner_points;        // the points with inner set
  std::vector<int> repaired_by;         // scratch: the last region of this batch's repair holding the point, else −1
  std::vector<int> patch_vertices;      // the points with repaired_by set
  std::vector<std::pair<std::array<int, 3>, int>> patch_faces;  // boundary triangles at them, with their region
  Eigen::Index received = 0, duplicates = 0;
  std::size_t pending_count = 0, wider = 0;
  Vertex hint;
  bool started = false;
  unsigned batch = 0;  // batches so far (CellInfo::filled)
  // Where to start locating a new point: a point already in, in the same
  // cell of a grid of side `hint_side` (one per cell, the last inserted).
  // A batch spread over the surface (random order) has consecutive points
  // ten spacings apart or more at 1%, and the walk from the last point was
  // 44% of the batch at 1M points. Rebuilt whenever the points doubled.
  U64Map<Vertex> hint_grid;
  double hint_side = 0.0;
  Eigen::Vector3d hint_origin = Eigen::Vector3d::Zero();
  std::size_t hint_built_at = 0;
  bool use_hints = false;  // for the batch being inserted
  std::size_t joined_faces = 0;  // cone triangles of the points joined in this batch

  // Scratch of find_zone and insert_in_zone for one new point: its conflict zone (the cells
  // Bowyer–Watson insertion deletes) and the zone's boundary facets, each
  // seen from inside, with the cell outside it (which insertion keeps: the
  // new cell on the facet is its neighbour there) and the flag of the cell
  // inside; where the boundary crosses the zone's boundary (joinable).
  struct HoleFacet {
    Cell outer;
    int mirror;  // the facet's index in outer
    char kept;   // of the deleted cell inside
  };
  std::vector<Cell> conflict;
  std::vector<Delaunay::Facet> hole;
  std::vector<HoleFacet> hole_facets;
  std::vector<std::array<int, 2>> crossing;     // the hole's edges between a kept and a removed facet, sorted
  std::vector<int> crossing_points;             // their points, sorted
  std::vector<std::array<int, 2>> disc_edges;   // edges of the boundary triangles inside the zone, sorted
  std::vector<std::pair<int, int>> f_change;    // (point, change of f) when the point joins
  int tip = -1;                                 // joinable_by_one_cell's facet, else −1
  // Per batch: the finite points of each new point's conflict zone (all
  // but the infinite vertex), each once, zone_points[zone_from[k],
  // zone_from[k + 1]) for the k-th point inserted; which new points were
  // joined (in the order of `fresh`). Listed by number, read off the
  // vertices while the insertion has them at hand: later passes over the
  // handles missed the cache at every vertex (at 1M points, random order).
  std::vector<int> zone_points;
  std::vector<std::size_t> zone_from;
  std::vector<Vertex> zone_vertex;  // the k-th point inserted
  unsigned zone_stamp = 0;          // the zone being listed (ZoneVertex::zone)
  std::vector<char> fresh_joined;

  // The finite cells around each point, found by a walk across the faces at
  // the point, all stars in one array. Insertion alone changes them: a
  // batch's stars are kept for the next one where its insertion left them
  // as they were (carry_stars_over), which in scan order is most of the
  // next repair's points (the margin rings move on by a batch's width).
  std::vector<int> star_slot;  // per point: its entry in star_range, else −1
  std::vector<std::array<std::size_t, 2>> star_range;
  std::vector<int> star_hull;      // per entry of star_range: the infinite cells around the point (its hull triangles)
  std::vector<char> star_used;     // per entry of star_range: asked for in this batch
  std::vector<Cell> star_cells;
  std::vector<int> starred;          // the points with a slot, in the order their stars were found
  std::vector<char> star_changed;    // scratch: the insertion changed the point's star
  std::vector<Cell> walk;
  unsigned visit_stamp = 0;

  // Infinite cells are never kept: their flag is cleared where they appear
  // (constrict_all for all of them; star() for those around new points —
  // every cell insertion adds to the hull has a new point), so the flag alone
  // answers without testing the cell's vertices against the infinite one.
  bool kept(Cell c) const { return c->info().kept; }

  // A fresh mark for CellInfo::visit.
  unsigned next_visit() {
    if (++visit_stamp == 0) {  // wrapped: no cell may look visited
      for (const Cell c : dt.all_cell_handles()) c->info().visit = 0;
      visit_stamp = 1;
    }
    return visit_stamp;
  }

  struct Star {
    const Cell* first;
    const Cell* last;
    const Cell* begin() const { return first; }
    const Cell* end() const { return last; }
  };
  // Valid until the next call (the array may grow).
  Star star(Vertex v) {
    int& slot = star_slot[static_cast<std::size_t>(v->info())];
    if (slot < 0) {
      slot = static_cast<int>(star_range.size());
      starred.push_back(v->info());
      const std::size_t from = star_cells.size();
      const unsigned stamp = next_visit();
      int on_hull = 0;
      walk.assign(1, v->cell());
      v->cell()->info().visit = stamp;
      while (!walk.empty()) {
        const Cell c = walk.back();
        walk.pop_back();
        if (!dt.is_infinite(c)) star_cells.push_back(c);
        else {
          ++on_hull;
          c->info().kept = 0;
        }
        for (int i = 0; i < 4; ++i) {
          if (c->vertex(i) == v) continue;
          const Cell n = c->neighbor(i);
          if (n->info().visit != stamp) {
            n->info().visit = stamp;
            walk.push_back(n);
          }
        }
      }
      star_range.push_back({from, star_cells.size()});
      star_hull.push_back(on_hull);
      star_used.push_back(0);
    }
    star_used[static_cast<std::size_t>(slot)] = 1;
    const auto& r = star_range[static_cast<std::size_t>(slot)];
    return {star_cells.data() + r[0], star_cells.data() + r[1]};
  }
  // After a batch's insertion: keeps the stars the last batch used that the
  // insertion did not change, forgets the others. A point's star changes
  // exactly when a cell around it is deleted, i.e. when it is a point of a
  // new point's conflict zone (zone_points).
  void carry_stars_over() {
    std::vector<int> changed;
    for (const int point : zone_points) {
      const auto id = static_cast<std::size_t>(point);
      if (star_slot[id] >= 0 && !star_changed[id]) {
        star_changed[id] = 1;
        changed.push_back(static_cast<int>(id));
      }
    }
    // Kept stars move down in place, in their order (a star's slot is its
    // entry in `starred`, and the ranges follow that order).
    std::size_t points_kept = 0, cells_kept = 0;
    for (std::size_t slot = 0; slot < starred.size(); ++slot) {
      const int id = starred[slot];
      if (star_changed[static_cast<std::size_t>(id)] || !star_used[slot]) {
        star_slot[static_cast<std::size_t>(id)] = -1;
        continue;
      }
      const auto [from, to] = star_range[slot];
      std::copy(star_cells.begin() + static_cast<std::ptrdiff_t>(from), star_cells.begin() + static_cast<std::ptrdiff_t>(to),
                star_cells.begin() + static_cast<std::ptrdiff_t>(cells_kept));
      star_range[points_kept] = {cells_kept, cells_kept + (to - from)};
      star_hull[points_kept] = star_hull[slot];
      starred[points_kept] = id;
      star_slot[static_cast<std::size_t>(id)] = static_cast<int>(points_kept);
      cells_kept += to - from;
      ++points_kept;
    }
    for (const int id : changed) star_changed[static_cast<std::size_t>(id)] = 0;
    starred.resize(points_kept);
    star_range.resize(points_kept);
    star_hull.resize(points_kept);
    star_used.assign(points_kept, 0);
    star_cells.resize(cells_kept);
  }

  // The boundary triangles at each of `at` (as their edges opposite the
  // point): link[first[k], first[k + 1]) are those at at[k]. Each cell
  // around the points is looked at once, for all of its points that ask: a
  // cell is around four points, and a region's points are mostly all asked
  // about at once.
  void boundary_links(const std::vector<Vertex>& at, std::vector<LinkEdge>& link, std::vector<std::size_t>& first) {
    for (const Vertex v : at) star(v);  // found now: the loop below walks no more (walks use the cells' marks)
    for (std::size_t k = 0; k < at.size(); ++k) local_vertex[static_cast<std::size_t>(at[k]->info())] = static_cast<int>(k);
    std::vector<std::pair<int, LinkEdge>> found;  // (k, edge at at[k])
    std::vector<Cell> looked;
    for (const Vertex v : at)
      for (const Cell c : star(v)) {
        if (c->info().local == 0) continue;
        c->info().local = 0;
        looked.push_back(c);
        if (!c->info().kept) continue;
        for (int i = 0; i < 4; ++i) {
          if (kept(c->neighbor(i))) continue;
          for (int a = 1; a < 4; ++a) {  // the triangle opposite i, at its point (i + a) % 4
            const int k = local_vertex[static_cast<std::size_t>(c->vertex((i + a) % 4)->info())];
            if (k >= 0) found.push_back({k, {c->vertex((i + a % 3 + 1) % 4), c->vertex((i + (a + 1) % 3 + 1) % 4)}});
          }
        }
      }
    for (const Cell c : looked) c->info().local = -1;
    for (const Vertex v : at) local_vertex[static_cast<std::size_t>(v->info())] = -1;
    first.assign(at.size() + 1, 0);  // counting sort by point
    for (const auto& [k, e] : found) ++first[static_cast<std::size_t>(k) + 1];
    std::partial_sum(first.begin(), first.end(), first.begin());
    link.resize(found.size());
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (const auto& [k, e] : found) link[next[static_cast<std::size_t>(k)]++] = e;
  }

  // The distinct finite vertices of `cells`.
  std::vector<Vertex> vertices_of(const std::vector<Cell>& cells) {
    std::vector<Vertex> out;
    for (const Cell c : cells)
      for (int k = 0; k < 4; ++k) {
        const Vertex v = c->vertex(k);
        if (local_vertex[static_cast<std::size_t>(v->info())] < 0) {
          local_vertex[static_cast<std::size_t>(v->info())] = static_cast<int>(out.size());
          out.push_back(v);
        }
      }
    for (const Vertex v : out) local_vertex[static_cast<std::size_t>(v->info())] = -1;
    return out;
  }

  // Adds to `region` the finite cells around its vertices that `wanted`
  // accepts and that are not in it yet.
  template <typename Wanted>
  void grow(std::vector<Cell>& region, Wanted&& wanted) {
    for (const Cell c : region) c->info().local = 0;
    for (const Vertex v : vertices_of(region)) {
      for (const Cell c : star(v))
        if (c->info().local < 0 && wanted(c)) {
          c->info().local = 0;
          region.push_back(c);
        }
    }
    for (const Cell c : region) c->info().local = -1;
  }

  // Fills the removed cells around v (their kept flag marks them as region).
  void fill_around(Vertex v, std::vector<Cell>& region) {
    for (const Cell c : star(v))
      if (!c->info().kept) {
        c->info().kept = 1;
        region.push_back(c);
      }
  }

  // Fills the pockets the fill enclosed: components of removed cells next to
  // the region that reach neither the outside of the hull nor more cells than
  // the region has (beyond that they count as outside). Only the cells
  // region[from, end) are looked around: a component of removed cells is
  // split (and a part of it enclosed) only by filling cells next to it, and
  // the cells filled before were looked around already. Returns whether it
  // found any.
  bool fill_pockets(std::vector<Cell>& region, std::size_t from) {
    const std::size_t budget = 4 * region.size() + 256;
    std::vector<Cell> component, seen;
    bool found = false;
    const std::size_t size = region.size();
    for (std::size_t r = from; r < size; ++r)
      for (int i = 0; i < 4; ++i) {
        const Cell start = region[r]->neighbor(i);
        if (dt.is_infinite(start) || start->info().kept || start->info().local >= 0) continue;
        // Flood the removed cells from here, marking them (local = 0).
        component.assign(1, start);
        start->info().local = 0;
        bool outside = false;
        for (std::size_t k = 0; k < component.size() && !outside; ++k)
          for (int j = 0; j < 4 && !outside; ++j) {
            const Cell n = component[k]->neighbor(j);
            if (dt.is_infinite(n)) outside = true;
            else if (!n->info().kept && n->info().local < 0) {
              n->info().local = 0;
              component.push_back(n);
              outside = component.size() > budget;
            }
          }
        seen.insert(seen.end(), component.begin(), component.end());
        if (outside) continue;
        found = true;
        for (const Cell c : component) {
          c->info().kept = 1;
          region.push_back(c);
        }
      }
    for (const Cell c : seen) c->info().local = -1;
    return found;
  }

  // The connected parts of the fill (joined through shared points), kept up
  // to date as the fill grows: a union-find over its points, which only
  // ever merges, so each round adds the cells filled since the last one
  // instead of walking the whole fill again.
  struct FillParts {
    std::vector<Vertex> vertices;  // in the order of their first cells in the fill
    std::vector<int> ids;          // their numbers (info)
    std::vector<int> parent;
    std::vector<int> size;         // of the set, at its root
    std::vector<int> cell_point;   // per cell in, the number of its vertex 0
    std::vector<unsigned> seen;    // per point: the last call of add_cells that listed it
    unsigned call = 0;
    std::size_t cells = 0;         // region[0, cells) are in
    int find(int a) {
      while (parent[static_cast<std::size_t>(a)] != a)
        a = parent[static_cast<std::size_t>(a)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
      return a;
    }
    // The smaller set under the larger: its trees stay shallow (a root of
    // a fill of 25k cells was otherwise reached through long chains).
    // Which point ends as root does not matter to the callers.
    void unite(int a, int b) {
      a = find(a);
      b = find(b);
      if (a == b) return;
      if (size[static_cast<std::size_t>(a)] < size[static_cast<std::size_t>(b)]) std::swap(a, b);
      parent[static_cast<std::size_t>(b)] = a;
      size[static_cast<std::size_t>(a)] += size[static_cast<std::size_t>(b)];
    }
  };
  // A point's number in p (p.vertices are left out when given by number).
  int fill_number(FillParts& p, int point) {
    int& n = fill_vertex[static_cast<std::size_t>(point)];
    if (n < 0) {
      n = static_cast<int>(p.ids.size());
      p.ids.push_back(point);
      p.parent.push_back(n);
      p.size.push_back(1);
    }
    return n;
  }
  int fill_number(FillParts& p, Vertex v) {
    const std::size_t before = p.ids.size();
    const int n = fill_number(p, v->info());
    if (p.ids.size() != before) p.vertices.push_back(v);
    return n;
  }
  // Adds region[p.cells, end) to p; returns the distinct points of those
  // cells, in the order they first appear there.
  std::vector<Vertex> add_cells(FillParts& p, const std::vector<Cell>& region) {
    std::vector<Vertex> added;
    ++p.call;
    for (; p.cells < region.size(); ++p.cells) {
      const Cell c = region[p.cells];
      int a = -1;
      for (int k = 0; k < 4; ++k) {
        const Vertex v = c->vertex(k);
        const int n = fill_number(p, v);
        if (static_cast<std::size_t>(n) == p.seen.size()) p.seen.push_back(0);
        if (p.seen[static_cast<std::size_t>(n)] != p.call) {
          p.seen[static_cast<std::size_t>(n)] = p.call;
          added.push_back(v);
        }
        if (k == 0) {
          a = n;
          p.cell_point.push_back(a);
        } else {
          p.unite(a, n);
        }
      }
    }
    return added;
  }
  void forget(const FillParts& p) {
    for (const int id : p.ids) fill_vertex[static_cast<std::size_t>(id)] = -1;
  }

  // The Euler characteristic's change (in sixths, see euler_share) per
  // connected part of the fill: the boundary triangles at a point change
  // only with the cells around it, so each part changes χ as if it were
  // filled alone, and a handle in one part is found (and repaired) there,
  // not in the whole fill. Returns the points of the parts whose change is
  // not 0 (f_now holds f(v) at every point of the fill).
  std::vector<Vertex> handle_parts(const std::vector<Cell>& region, FillParts& p) {
    add_cells(p, region);
    std::vector<int> change(p.vertices.size(), 0);  // per root
    std::vector<int> root(p.vertices.size());
    for (std::size_t k = 0; k < p.vertices.size(); ++k) {
      const auto id = static_cast<std::size_t>(p.ids[k]);
      root[k] = p.find(static_cast<int>(k));
      change[static_cast<std::size_t>(root[k])] += euler_share(f_now[id]) - euler_share(faces_at[id]);
    }
    std::vector<Vertex> out;
    for (std::size_t k = 0; k < p.vertices.size(); ++k)
      if (change[static_cast<std::size_t>(root[k])] != 0) out.push_back(p.vertices[k]);
    return out;
  }

  // Whether a region is small enough for a local repair: at most
  // local_share of the triangulation's cells (see fill_to_ball).
  bool local(const std::vector<Cell>& region) const {
    return static_cast<double>(region.size()) <= local_share * static_cast<double>(dt.number_of_cells());
  }

  // Makes sure the filled solid is still a ball: at every point whose star
  // changed the boundary must be a 2-manifold (its link one cycle), and the
  // Euler characteristic must stay 2 (a handle lowers it, an enclosed pocket
  // raises it). Where the fill pinched the boundary at a point, the removed
  // cells around that point are filled too; where a part of the fill changed
  // the Euler characteristic, those around every point of that part. Returns
  // false when that does not settle within a few rounds, or when the fill
  // grows beyond local_share of the triangulation's cells: its local
  // complex, with the cells around its points, would then hold most of the
  // triangulation, and the fill's rounds and the local constrictions (with
  // a ring released where a part locks) cost more than constricting the
  // whole once (docs/design.md, "Too wide to be local"). `parts` ends as
  // the connected parts of the fill. Every finite cell across a face of
  // region[0, enclosed) is in the region: no pocket is looked for there.
  bool fill_to_ball(std::vector<Cell>& region, FillParts& parts, std::size_t enclosed) {
    // f(v) now (−1: unchanged since the last batch) and whether v is pinched,
    // refreshed only at the points of cells filled since the last round.
    std::vector<Vertex> known, linked;
    std::vector<LinkEdge> link;
    std::vector<std::size_t> first;
    const auto refresh = [&](const std::vector<Vertex>& points) {
      linked.clear();
      for (const Vertex v : points) {
        const auto id = static_cast<std::size_t>(v->info());
        if (f_now[id] < 0) known.push_back(v);
        if (inner[id] >= 0) {  // every finite cell around v is filled: its hull triangles alone
          f_now[id] = inner[id];
          pinched_now[id] = 0;
        } else {
          linked.push_back(v);
        }
      }
      boundary_links(linked, link, first);
      for (std::size_t k = 0; k < linked.size(); ++k) {
        const auto id = static_cast<std::size_t>(linked[k]->info());
        f_now[id] = static_cast<int>(first[k + 1] - first[k]);
        pinched_now[id] = !single_cycle(std::span<const LinkEdge>(link).subspan(first[k], first[k + 1] - first[k]));
      }
    };
    bool ball = false;
    std::size_t pockets_checked = enclosed;
    std::vector<Vertex> pinched;
    for (int round = 0; round < kFillRounds && !ball; ++round) {
      if (!local(region)) break;  // the whole is constricted again
      // A point's pinch changes only with its star: the candidates are the
      // points of the cells filled since the last round (added to the
      // parts now) and those pinched before.
      std::vector<Vertex> candidates = add_cells(parts, region);
      refresh(candidates);
      candidates.insert(candidates.end(), pinched.begin(), pinched.end());
      pinched.clear();
      for (const Vertex v : candidates) {
        char& p = pinched_now[static_cast<std::size_t>(v->info())];
        if (p == 1) pinched.push_back(v);
        p = p ? 2 : 0;  // 2: listed
      }
      for (const Vertex v : pinched) pinched_now[static_cast<std::size_t>(v->info())] = 1;
      if (!pinched.empty()) {
        for (const Vertex v : pinched) fill_around(v, region);
      } else if (const std::size_t before = region.size(); fill_pockets(region, pockets_checked)) {
        pockets_checked = before;  // the pockets' own cells border only kept or filled cells
      } else {  // a pocket and a handle would cancel out in χ
        pockets_checked = before;
        const std::vector<Vertex> handles = handle_parts(region, parts);
        ball = handles.empty();
        for (const Vertex v : handles) fill_around(v, region);
      }
    }
    for (const Vertex v : known) {
      f_now[static_cast<std::size_t>(v->info())] = -1;
      pinched_now[static_cast<std::size_t>(v->info())] = 0;
    }
    return ball;
  }

  // With `part`, the region is one connected part of the fill as the fill
  // check left it and `part` its points in the order of their first cells
  // there (as FillParts numbered them), so they are not read off the cells
  // again; and the cells around a point inner to the fill (inner) are all
  // in the part, so its star adds nothing to the surround and is not read.
  LocalComplex local_complex(const std::vector<Cell>& region, bool surround, const std::vector<Vertex>* part) {
    LocalComplex L;
    const auto add_cell = [&](Cell c) {
      c->info().local = static_cast<int>(L.cells.size());
      L.cells.push_back(c);
    };
    const auto add_vertices = [&](std::size_t from) {
      for (std::size_t i = from; i < L.cells.size(); ++i)
        for (int k = 0; k < 4; ++k) {
          const Vertex v = L.cells[i]->vertex(k);
          int& id = local_vertex[static_cast<std::size_t>(v->info())];
          if (id < 0) {
            id = static_cast<int>(L.vertices.size());
            L.vertices.push_back(v);
          }
        }
    };
    for (const Cell c : region) add_cell(c);
    L.region = L.cells.size();
    if (part) {
      L.vertices = *part;
      for (std::size_t k = 0; k < L.vertices.size(); ++k)
        local_vertex[static_cast<std::size_t>(L.vertices[k]->info())] = static_cast<int>(k);
    } else {
      add_vertices(0);
    }
    L.core_vertices = L.vertices.size();
    if (surround) {
      for (std::size_t k = 0; k < L.core_vertices; ++k) {
        if (part && inner[static_cast<std::size_t>(L.vertices[k]->info())] >= 0) continue;
        for (const Cell c : star(L.vertices[k]))
          if (c->info().local < 0) add_cell(c);
      }
      add_vertices(L.region);
    }
    const auto cells = static_cast<Eigen::Index>(L.cells.size());
    L.dt.points.resize(static_cast<Eigen::Index>(L.vertices.size()), 3);
    for (std::size_t k = 0; k < L.vertices.size(); ++k)
      L.dt.points.row(static_cast<Eigen::Index>(k)) = points[static_cast<std::size_t>(L.vertices[k]->info())].transpose();
    L.dt.cells.resize(cells, 4);
    L.dt.neighbors.resize(cells, 4);
    L.start.kept.resize(L.cells.size());
    L.guides.resize(L.cells.size());
    for (Eigen::Index i = 0; i < cells; ++i) {
      const Cell c = L.cells[static_cast<std::size_t>(i)];
      L.start.kept[static_cast<std::size_t>(i)] = c->info().kept;
      L.guides[static_cast<std::size_t>(i)] = c->info().guides;
      for (int k = 0; k < 4; ++k) {
        L.dt.cells(i, k) = local_vertex[static_cast<std::size_t>(c->vertex(k)->info())];
        const Cell n = c->neighbor(k);
        L.dt.neighbors(i, k) = n->info().local;  // −1 for infinite cells too: they are in no complex
      }
    }
    if (surround) {
      L.start.frozen.assign(L.cells.size(), 1);
      std::fill(L.start.frozen.begin(), L.start.frozen.begin() + static_cast<std::ptrdiff_t>(L.region), 0);
      L.start.exempt.resize(L.vertices.size());
      for (std::size_t k = 0; k < L.vertices.size(); ++k)
        L.start.exempt[k] = pending[static_cast<std::size_t>(L.vertices[k]->info())];
    }
    for (const Cell c : L.cells) c->info().local = -1;
    for (const Vertex v : L.vertices) local_vertex[static_cast<std::size_t>(v->info())] = -1;
    return L;
  }

  // The constriction options for L: the cells between its points and their
  // viewpoints, among those re-decided, are carved first. A line is followed
  // within L only: where it leaves L it ends, as at the convex hull.
  ConstrictionOptions with_sight_lines(const LocalComplex& L, BatchStats& stats) const {
    std::vector<SightLine> lines;
    for (std::size_t k = 0; k < L.vertices.size(); ++k) {
      const int view = viewpoint_of[static_cast<std::size_t>(L.vertices[k]->info())];
      if (view >= 0) lines.push_back({static_cast<int>(k), viewpoints[static_cast<std::size_t>(view)]});
    }
    if (lines.empty()) return constriction;
    ConstrictionOptions options = constriction;
    options.carve_first =
        line_of_sight_depths(L.dt, L.dt.points, lines, static_cast<Eigen::Index>(L.core_vertices));
    for (std::size_t i = L.region; i < L.cells.size(); ++i) options.carve_first[i] = -1;  // frozen or outside already
    for (std::size_t i = 0; i < L.region; ++i) stats.sight_line_cells += options.carve_first[i] >= 0;
    return options;
  }

  // Records f(v) for the points of a region whose result was kept, from the
  // boundary of its complex: every boundary triangle at a point of the
  // region is a face of a cell around that point, so of the complex, and the
  // complex's own edge (its removed or frozen cells' faces to cells outside
  // it) has no point of the region. `piece` numbers the region within the
  // batch; the triangles at its points are kept for patch_size.
  void record_faces(const LocalComplex& L, const Constriction<3>& r, int piece) {
    std::vector<int> f(L.core_vertices, 0);
    for (Eigen::Index t = 0; t < r.boundary.rows(); ++t) {
      bool at_core = false;
      std::array<int, 3> face{};
      for (int k = 0; k < 3; ++k) {
        const auto v = static_cast<std::size_t>(r.boundary(t, k));
        if (v < L.core_vertices) {
          ++f[v];
          at_core = true;
        }
        face[static_cast<std::size_t>(k)] = L.vertices[v]->info();
      }
      if (at_core) patch_faces.push_back({face, piece});
    }
    for (std::size_t k = 0; k < L.core_vertices; ++k) {
      const auto id = static_cast<std::size_t>(L.vertices[k]->info());
      corners += f[k] - faces_at[id];
      faces_at[id] = f[k];
      if (repaired_by[id] < 0) patch_vertices.push_back(static_cast<int>(id));
      repaired_by[id] = piece;
    }
  }

  // The boundary triangles at the points of the regions recorded since the
  // last call, each counted once: a triangle is counted in the last region
  // that had one of its points (a later region re-decided the cells around
  // that point, so its result holds the triangle if it is still there).
  std::size_t patch_size() {
    std::size_t n = 0;
    for (const auto& [face, piece] : patch_faces) {
      int last = -1;
      for (const int v : face) last = std::max(last, repaired_by[static_cast<std::size_t>(v)]);
      n += last == piece;
    }
    for (const int v : patch_vertices) repaired_by[static_cast<std::size_t>(v)] = -1;
    patch_vertices.clear();
    patch_faces.clear();
    return n;
  }

  // Whether a frozen cell of L is within two steps of a point the local
  // constriction locked (interior, not pending): a cell around it or around
  // one of its neighbours. Only then can releasing kept cells around the
  // region bring it on. Measured (docs/design.md): every lock at 100k and 1M
  // points in scan order was a point whose whole star was re-decided and
  // whose way out was held by the rules themselves — a cell with its one
  // boundary face opposite the point, held by the γ-guide, or blocked by
  // removability (§5.3) — the points a from-scratch constriction of the same
  // points leaves interior too, so the released ring only doubled the work.
  bool frozen_near(const LocalComplex& L, const std::vector<char>& interior) const {
    const auto& cells = L.dt.cells;
    std::vector<char> near(L.vertices.size(), 0);
    for (std::size_t k = 0; k < L.core_vertices; ++k)
      near[k] = interior[k] && !pending[static_cast<std::size_t>(L.vertices[k]->info())];
    for (int step = 0; step < 2; ++step) {  // near: the locked points, then their neighbours too
      std::vector<char> grown = near;
      for (Eigen::Index i = 0; i < cells.rows(); ++i) {
        bool touches = false;
        for (int k = 0; k < 4; ++k) touches = touches || near[static_cast<std::size_t>(cells(i, k))];
        if (!touches) continue;
        if (step == 1 && static_cast<std::size_t>(i) >= L.region && L.start.kept[static_cast<std::size_t>(i)]) return true;
        for (int k = 0; k < 4; ++k) grown[static_cast<std::size_t>(cells(i, k))] = 1;
      }
      near = std::move(grown);
    }
    return false;
  }

  // Constricts the region (kept cells around it frozen when `surround`);
  // keeps the result when every point of the region that is not pending
  // reached the boundary, or when `final`, and then, for a region `piece`
  // ≥ 0 of a local repair, records f(v) at its points (record_faces); it
  // keeps a locked result too when no frozen cell is near the points that
  // locked (frozen_near: releasing a ring would not bring them on). Returns
  // whether the result was kept.
  bool constrict_region(const std::vector<Cell>& region, bool surround, bool final, BatchStats& stats, int piece = -1,
                        const std::vector<Vertex>* part = nullptr) {
    LocalComplex L = local_complex(region, surround, part);
    L.start.guides = &L.guides;
    stats.tetrahedra_touched += L.cells.size();
    const Constriction<3> r = constrict(L.dt, L.start, with_sight_lines(L, stats));
    for (std::size_t i = 0; i < L.region; ++i) L.cells[i]->info().guides = L.guides[i];
    std::vector<char> interior(L.vertices.size(), 0);
    for (const int v : r.interior_vertices) interior[static_cast<std::size_t>(v)] = 1;
    bool reached = true;
    for (std::size_t k = 0; k < L.core_vertices; ++k)
      reached = reached && (!interior[k] || pending[static_cast<std::size_t>(L.vertices[k]->info())]);
    // A lock no frozen cell is near is kept as it is (see frozen_near).
    const bool held = !reached && !final && surround && !frozen_near(L, interior);
    if (!reached && !final && !held) return false;
    for (std::size_t i = 0; i < L.region; ++i) L.cells[i]->info().kept = r.kept[i];
    for (std::size_t k = 0; k < L.core_vertices; ++k) {
      char& p = pending[static_cast<std::size_t>(L.vertices[k]->info())];
      pending_count += static_cast<std::size_t>(interior[k]) - static_cast<std::size_t>(p);
      p = interior[k];
    }
    if (piece >= 0) record_faces(L, r, piece);
    return reached || held;
  }

  // The wider repair (and the first constriction): all of the convex hull
  // kept, constricted as a whole, exactly as reconstruct_surface does.
  void constrict_all(BatchStats& stats) {
    std::vector<Cell> all;
    std::vector<Cell> hull;
    dt.incident_cells(dt.infinite_vertex(), std::back_inserter(hull));
    for (const Cell c : hull) c->info().kept = 0;
    for (const Cell c : dt.finite_cell_handles()) {
      c->info().kept = 1;
      all.push_back(c);
    }
    std::fill(pending.begin(), pending.end(), 0);
    pending_count = 0;
    constrict_region(all, false, true, stats);
    std::fill(faces_at.begin(), faces_at.end(), 0);
    corners = 0;
    for (const Cell c : all)
      if (c->info().kept)
        for (int i = 0; i < 4; ++i)
          if (!kept(c->neighbor(i))) {
            corners += 3;
            for (int k = 1; k < 4; ++k) ++faces_at[static_cast<std::size_t>(c->vertex((i + k) % 4)->info())];
          }
  }

  // Whether a cell is kept, the flag of an infinite cell not read (it is
  // cleared only where star() meets it); a point's number, −1 for the
  // infinite vertex.
  char inside(Cell c) const { return !dt.is_infinite(c) && c->info().kept; }
  int point_id(Vertex v) const { return dt.is_infinite(v) ? -1 : v->info(); }

  // Joining a new point to the boundary without re-constriction. The
  // boundary crosses the new point's conflict zone (a ball) in the
  // triangles between its kept and removed cells, a surface whose border
  // (mod 2) is the crossing curve on the zone's boundary: the edges between
  // a facet over a kept cell and one over a removed cell. Insertion fills
  // the zone with the cone from the point over its boundary facets; each
  // new cell takes the flag of the deleted cell on its facet, so the new
  // boundary inside the zone is the cone over the crossing curve. When the
  // old one is a disk whose border is one simple cycle of m edges and holds
  // all of its points (m − 2 triangles, each inner edge in two of them,
  // each border edge in one), one disk takes another's place along the
  // same cycle: the surface stays a closed 2-manifold of the same genus,
  // every point stays on it (the cone keeps the cycle's points) and the new
  // point is on it. Its triangles are Delaunay faces, so it stays simple. A
  // point outside the hull is no exception: with the infinite vertex the
  // triangulation is one of the 3-sphere, its infinite cells outside, and
  // no boundary triangle has the infinite vertex. Not joinable: a zone
  // reaching into cells filled in this batch, or any other crossing; those
  // points are filled and re-decided by repair(). A point the boundary does
  // not cross: joinable_by_one_cell. f_change holds the changes of f(v).
  bool joinable(const Kernel::Point_3& p) {
    const unsigned stamp = next_visit();
    for (const Cell c : conflict) {
      if (c->info().filled == batch) return false;
      c->info().visit = stamp;
    }
    // The old boundary inside the zone (its triangles between two deleted
    // cells), and its edges.
    disc_edges.clear();
    f_change.clear();
    std::size_t triangles = 0;
    for (const Cell c : conflict)
      for (int j = 0; j < 4; ++j) {
        const Cell n = c->neighbor(j);
        if (n->info().visit != stamp || !(c < n) || inside(n) == inside(c)) continue;
        ++triangles;
        int v[3];
        for (int k = 0; k < 3; ++k) {
          v[k] = c->vertex((j + k + 1) & 3)->info();
          f_change.push_back({v[k], -1});
        }
        for (int k = 0; k < 3; ++k) disc_edges.push_back({std::min(v[k], v[(k + 1) % 3]), std::max(v[k], v[(k + 1) % 3])});
      }
    tip = -1;
    if (triangles == 0) return joinable_by_one_cell(p);  // all deleted cells on one side
    if (triangles + 2 > kMaxJoinCycle) return false;
    // Its border (edges in one triangle; mod 2 it is the crossing curve)
    // and its inner edges (in two).
    std::sort(disc_edges.begin(), disc_edges.end());
    crossing.clear();
    for (std::size_t j = 0; j < disc_edges.size();) {
      std::size_t run = 1;
      while (j + run < disc_edges.size() && disc_edges[j + run] == disc_edges[j]) ++run;
      if (run == 1) {
        crossing.push_back(disc_edges[j]);
      } else if (run != 2) {
        return false;
      }
      j += run;
    }
    const std::size_t m = crossing.size();
    if (triangles + 2 != m) return false;  // not a disk with every point on its border
    // One simple cycle: every point on it twice, one walk round covers it.
    crossing_points.clear();
    for (const auto& e : crossing) crossing_points.insert(crossing_points.end(), e.begin(), e.end());
    std::sort(crossing_points.begin(), crossing_points.end());
    for (std::size_t j = 0; j < 2 * m; j += 2)
      if (crossing_points[j] != crossing_points[j + 1] || (j + 2 < 2 * m && crossing_points[j + 2] == crossing_points[j]))
        return false;
    crossing_points.erase(std::unique(crossing_points.begin(), crossing_points.end()), crossing_points.end());
    std::size_t steps = 1, last = 0;
    for (int at = crossing[0][1]; at != crossing[0][0]; ++steps) {
      if (steps == m) return false;
      std::size_t e = 0;
      while (e == last || (crossing[e][0] != at && crossing[e][1] != at)) ++e;
      at = crossing[e][0] == at ? crossing[e][1] : crossing[e][0];
      last = e;
    }
    if (steps != m) return false;
    // Every point of the disk is on its border: no point leaves the boundary.
    for (const auto& [q, change] : f_change)
      if (!std::binary_search(crossing_points.begin(), crossing_points.end(), q)) return false;
    for (const int q : crossing_points) f_change.push_back({q, 2});  // two cone triangles at each
    return true;
  }

  // The boundary does not cross the zone: the point is inside the solid or
  // outside it. If a facet of the zone's boundary is a boundary triangle,
  // the new cell on it is removed (inside) or kept (outside), and every
  // other new cell takes its deleted cell's flag. Inside, that cell has
  // one boundary triangle and its opposite vertex, the new point, is not
  // on the boundary: a removal of §5.3, which keeps the solid a ball.
  // Outside, the cell is glued to the solid along that one triangle, the
  // inverse of such a removal. Of several facets, the one whose γ-indicator
  // (Definition 5.2) with respect to the new point is smallest (inside:
  // constriction's own choice) or largest (outside: the cell constriction
  // would remove last). Sets tip to the facet's entry in `hole`.
  bool joinable_by_one_cell(const Kernel::Point_3& p) {
    const char side = inside(conflict.front());  // the whole zone's
    const Eigen::Vector3d apex(p.x(), p.y(), p.z());
    double best = 0.0;
    for (std::size_t k = 0; k < hole.size(); ++k) {
      const auto& [c, i] = hole[k];
      if (inside(c->neighbor(i)) == side) continue;
      Eigen::Vector3d corner[3];
      for (int j = 0; j < 3; ++j) {
        const auto& q = c->vertex((i + j + 1) & 3)->point();
        corner[j] = Eigen::Vector3d(q.x(), q.y(), q.z());
      }
      const double g = gamma_indicator(corner[0], corner[1], corner[2], apex);
      if (tip < 0 || (side ? g < best : g > best)) {
        tip = static_cast<int>(k);
        best = g;
      }
    }
    if (tip < 0) return false;
    f_change.clear();
    const auto& [c, i] = hole[static_cast<std::size_t>(tip)];
    for (int j = 0; j < 3; ++j) f_change.push_back({c->vertex((i + j + 1) & 3)->info(), 1});  // one triangle for two
    return true;
  }

  // The grid cell of p (21 bits per axis: a far point shares a cell with
  // others, which only makes its walk longer).
  std::uint64_t hint_key(const Kernel::Point_3& p) const {
    const auto axis = [&](double x, double o) {
      const double k = std::floor((x - o) / hint_side);
      return static_cast<std::uint64_t>(std::clamp(k, 0.0, double((1 << 21) - 1)));
    };
    return axis(p.x(), hint_origin.x()) << 42 | axis(p.y(), hint_origin.y()) << 21 | axis(p.z(), hint_origin.z());
  }
  // (Re)builds the grid over the points so far: a side of twice the
  // spacing of the points spread over the box's faces (a surface sample; a
  // volume's points give the cube root of the box's volume per point if
  // that is larger), about four points to a cell on a surface.
  void build_hint_grid() {
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& q : points) box.extend(q);
    const Eigen::Vector3d d = box.sizes();
    const double n = static_cast<double>(points.size());
    const double faces = 2.0 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
    hint_side = std::max(2.0 * std::sqrt(faces / n), std::cbrt(d.prod() / n));
    hint_origin = box.min() - Eigen::Vector3d::Constant(hint_side * double(1 << 19));
    hint_grid = U64Map<Vertex>(points.size() / 4);
    hint_built_at = points.size();
    if (!(hint_side > 0.0) || !std::isfinite(hint_side)) {
      hint_side = 0.0;
      return;
    }
    for (const Vertex v : dt.finite_vertex_handles()) hint_grid[hint_key(v->point())] = v;
  }

  // Locates p (dimension 3) and finds its conflict zone (conflict, hole);
  // false for a point already in the triangulation.
  bool find_zone(const Kernel::Point_3& p) {
    Delaunay::Locate_type lt;
    int li = 0, lj = 0;
    if (use_hints)
      if (const Vertex* near = hint_grid.find(hint_key(p)); near && *near != Vertex()) hint = *near;
    const Cell at = dt.locate(p, lt, li, lj, hint == Vertex() ? Cell() : hint->cell());
    if (lt == Delaunay::VERTEX) {
      hint = at->vertex(li);
      return false;
    }
    conflict.clear();
    hole.clear();
    dt.find_conflicts(p, at, std::back_inserter(hole), std::back_inserter(conflict));
    return true;
  }

  // Inserts p as `id` into the zone find_zone found: joined to the boundary
  // (after joinable() said so), else with its new cells filled.
  Vertex insert_in_zone(const Kernel::Point_3& p, int id, bool joined) {
    hole_facets.clear();
    if (++zone_stamp == 0) {  // wrapped: no point may look listed
      for (const Vertex v : dt.finite_vertex_handles()) v->zone = 0;
      zone_stamp = 1;
    }
    for (const auto& [c, i] : hole) {
      hole_facets.push_back({c->neighbor(i), dt.mirror_index(c, i), inside(c)});
      // Each point is on about five facets: listed at the first.
      for (int k = 1; k < 4; ++k)
        if (const Vertex v = c->vertex((i + k) & 3); !dt.is_infinite(v)) {
          if (v->zone != zone_stamp) {
            v->zone = zone_stamp;
            zone_points.push_back(v->info());
          }
        }
    }
    zone_from.push_back(zone_points.size());
    // As CGAL's own insert does (the same triangulation either way): a small
    // hole (nearly all) by the data structure's direct fill, others by the
    // recursive star from the last boundary facet.
    if (dt.tds().is_small_hole(hole.size())) {
      hint = dt.tds()._insert_in_small_hole(conflict, hole);
      hint->set_point(p);
    } else {
      hint = dt.insert_in_hole(p, conflict.begin(), conflict.end(), hole.back().first, hole.back().second);
    }
    hint->info() = id;
    zone_vertex.push_back(hint);
    if (use_hints) hint_grid[hint_key(p)] = hint;
    for (std::size_t k = 0; k < hole_facets.size(); ++k) {
      const HoleFacet& h = hole_facets[k];
      GuideMemo& outer = h.outer->info().guides;  // its neighbour there is new
      outer.known &= static_cast<std::uint8_t>(~(1u << h.mirror));
      outer.keep &= static_cast<std::uint8_t>(~(1u << h.mirror));
      CellInfo& info = h.outer->neighbor(h.mirror)->info();
      if (joined) {
        info.kept = static_cast<char>(h.kept != (static_cast<int>(k) == tip));
      } else {
        info.filled = batch;
      }
    }
    if (joined) {
      const std::size_t f = tip >= 0 ? 3 : crossing.size();
      faces_at.resize(static_cast<std::size_t>(id) + 1, 0);
      for (const auto& [q, change] : f_change) faces_at[static_cast<std::size_t>(q)] += change;
      faces_at[static_cast<std::size_t>(id)] = static_cast<int>(f);
      corners += 6;  // F = 2V − 4 grows by 2 (m cone triangles for m − 2; three for one)
      joined_faces += f;
    }
    return hint;
  }

  // Inserts the batch in spatial order (each point located from the last,
  // or in a scattered batch from the grid of hints), then numbers the new
  // points in the order of their rows. Returns the new points; `joined`
  // counts those joined to the boundary (joinable).
  std::vector<Vertex> insert(const Eigen::MatrixX3d& batch_points, std::size_t& joined) {
    std::vector<Indexed> input;
    input.reserve(static_cast<std::size_t>(batch_points.rows()));
    for (Eigen::Index i = 0; i < batch_points.rows(); ++i)
      input.emplace_back(Kernel::Point_3(batch_points(i, 0), batch_points(i, 1), batch_points(i, 2)), static_cast<int>(i));
    // CGAL's BRIO order (random rounds, each along a Hilbert curve), as
    // for a triangulation built from nothing: the first rounds spread over
    // the batch, and the later points then mostly fall inside their cells
    // instead of each conflicting with the long cells that span the part
    // not scanned yet from a scan front (a plain Hilbert order: insertion
    // 4.7–4.9 → 4.2–4.3 ms of a 100k scan-order batch, and new_cells 1.5 →
    // 1.0 ms; brio_hilbert_sort's order made new_cells 3.9 ms).
    // Its shuffle has a fixed seed: the order depends on the batch alone.
    CGAL::spatial_sort(input.begin(), input.end(), SortTraits());
    if (started && points.size() >= 64 && points.size() >= 2 * hint_built_at) build_hint_grid();
    // The grid serves a scattered batch only: where consecutive points (in
    // Hilbert order) lie within a grid cell of each other on average, as
    // along a scan front, the last point is as near, and the lookups and
    // updates (a likely cache miss each) only cost (about 1% of a
    // scan-order batch). A batch that skips the grid leaves it older, not
    // wrong.
    use_hints = false;
    if (hint_side > 0.0 && input.size() > 1) {
      double apart = 0.0;
      for (std::size_t k = 1; k < input.size(); ++k) apart += std::sqrt(CGAL::squared_distance(input[k - 1].first, input[k].first));
      use_hints = apart / static_cast<double>(input.size() - 1) > hint_side;
    }
    std::vector<std::tuple<int, Vertex, char>> created;  // row, vertex, joined
    const std::size_t base = points.size();
    zone_points.clear();
    zone_from.assign(1, 0);
    zone_vertex.clear();
    // New points are numbered in insertion order meanwhile (base + k).
    const auto add = [&](Vertex v, int row, bool joined_now) {
      if (v == Vertex()) {
        ++duplicates;
        return;
      }
      joined += joined_now;
      created.emplace_back(row, v, joined_now);
    };
    const auto next_id = [&] { return static_cast<int>(base + created.size()); };
    // Once a boundary exists, each point is joined if it can be
    // (joinable), else filled at once. (Letting it wait for a second pass,
    // with its neighbours in, joined 0.2% more points in random order, and
    // in scan order it joined front points that the front's fill re-opens
    // anyway: 7.0% of from scratch instead of 5.1% at 100k.)
    for (const auto& [point, row] : input) {
      if (dt.dimension() < 3) {
        const auto before = dt.number_of_vertices();
        hint = dt.insert(point, hint == Vertex() ? Cell() : hint->cell());
        const bool inserted = dt.number_of_vertices() != before;
        if (inserted) hint->info() = next_id();
        add(inserted ? hint : Vertex(), row, false);
      } else if (!find_zone(point)) {
        add(Vertex(), row, false);
      } else {
        const bool join = started && joinable(point);
        add(insert_in_zone(point, next_id(), join), row, join);
      }
    }
    std::sort(created.begin(), created.end(), [](const auto& a, const auto& b) { return std::get<0>(a) < std::get<0>(b); });
    faces_at.resize(base + created.size(), 0);
    std::vector<int> f(created.size());
    for (std::size_t k = 0; k < created.size(); ++k) f[k] = faces_at[static_cast<std::size_t>(std::get<1>(created[k])->info())];
    std::copy(f.begin(), f.end(), faces_at.begin() + static_cast<std::ptrdiff_t>(base));
    std::vector<Vertex> fresh;
    fresh_joined.clear();
    std::vector<int> renumbered(created.size());  // by the number given at insertion
    for (const auto& [row, v, joined_now] : created) {
      fresh_joined.push_back(joined_now);
      renumbered[static_cast<std::size_t>(v->info()) - base] = static_cast<int>(points.size());
      v->info() = static_cast<int>(points.size());
      points.push_back(batch_points.row(row).transpose());
      viewpoint_of.push_back(batch_viewpoint);
      source.push_back(received + row);
      fresh.push_back(v);
    }
    for (int& id : zone_points)
      if (static_cast<std::size_t>(id) >= base) id = renumbered[static_cast<std::size_t>(id) - base];
    faces_at.resize(points.size(), 0);
    local_vertex.resize(points.size(), -1);
    f_now.resize(points.size(), -1);
    star_slot.resize(points.size(), -1);
    pending.resize(points.size(), 0);
    pinched_now.resize(points.size(), 0);
    fill_vertex.resize(points.size(), -1);
    inner.resize(points.size(), -1);
    repaired_by.resize(points.size(), -1);
    star_changed.resize(points.size(), 0);
    received += batch_points.rows();
    return fresh;
  }

  // The new points' cells to re-decide: a scan front's all (filled, its
  // joined points' too), elsewhere the cells of the points not joined
  // (joinable). The new points are parted by their conflict zones: two are
  // in one part when their zones share a point (a union-find over the
  // zones' points), so two new points with a cell in common are; a part
  // holding a tenth of the batch's new points is a front. (Counting only
  // the points not joined, a batch of a tenth of the points so far in
  // random order was no front, and its joined points kept decisions taken
  // without them: hand's recall 1.9 points lower, batches of 5%.)
  void new_cells(const std::vector<Vertex>& fresh, std::vector<Cell>& front, std::vector<Cell>& rest) {
    FillParts zones;
    for (std::size_t k = 0; k < zone_vertex.size(); ++k) {
      const int a = fill_number(zones, zone_vertex[k]->info());
      for (std::size_t j = zone_from[k]; j < zone_from[k + 1]; ++j) zones.unite(a, fill_number(zones, zone_points[j]));
    }
    const auto part = [&](Vertex v) { return static_cast<std::size_t>(zones.find(fill_vertex[static_cast<std::size_t>(v->info())])); };
    std::vector<std::size_t> fresh_in(zones.ids.size(), 0);
    for (const Vertex v : fresh) ++fresh_in[part(v)];
    for (std::size_t k = 0; k < fresh.size(); ++k) {
      const bool in_front = 10 * fresh_in[part(fresh[k])] >= fresh.size();
      if (!in_front && fresh_joined[k]) continue;
      for (const Cell c : star(fresh[k])) {
        if (c->info().local >= 0) continue;
        if (in_front) {
          c->info().kept = 1;
          front.push_back(c);
        } else if (c->info().filled == batch) {
          rest.push_back(c);
        } else {
          continue;
        }
        c->info().local = 0;
      }
    }
    forget(zones);
    for (const Cell c : front) c->info().local = -1;
    for (const Cell c : rest) c->info().local = -1;
  }

  // The margin rings around the scan fronts' new cells (new_cells): where
  // the old boundary capped space not scanned yet and was carved without
  // these points. A part of a few points among many (a batch spread over
  // the surface, as in random order) refines the boundary where it already
  // was, and rings around every one of them would cover the whole surface.
  // `enclosed` ends as the number of cells at the start of the result whose
  // finite neighbours are all in it (the rings and the skin's inner layers).
  std::vector<Cell> with_margin(std::vector<Cell> front, const std::vector<Cell>& rest, std::size_t& enclosed) {
    enclosed = 0;
    if (margin == 0) {
      front.insert(front.end(), rest.begin(), rest.end());
      return front;
    }
    for (const Cell c : rest) c->info().local = 0;  // not taken into the front's rings
    for (const Cell c : front) c->info().local = 0;
    // A ring: the kept cells around every point of the front, then the
    // removed ones (filled) around every point of the front so grown. A
    // point whose kept (removed) cells were all taken in before has none
    // left out (no cell is removed here), so each step looks only around
    // the points it has not looked around yet, in the order they appeared.
    std::vector<Vertex> known;  // the points of front[0, scanned), in order of appearance (fill_vertex marks them)
    std::size_t scanned = 0, kept_done = 0, removed_done = 0;
    const auto add_points = [&] {
      for (; scanned < front.size(); ++scanned)
        for (int k = 0; k < 4; ++k) {
          const Vertex v = front[scanned]->vertex(k);
          int& mark = fill_vertex[static_cast<std::size_t>(v->info())];
          if (mark < 0) {
            mark = 0;
            known.push_back(v);
          }
        }
    };
    // A margin beyond the local share of the cells is not grown further:
    // fill_to_ball then gives the batch to the wider repair at once.
    for (int ring = 0; ring < margin && !front.empty() && local(front); ++ring) {
      add_points();
      for (const std::size_t end = known.size(); kept_done < end && local(front); ++kept_done)
        for (const Cell c : star(known[kept_done]))
          if (c->info().local < 0 && c->info().kept) {
            c->info().local = 0;
            front.push_back(c);
          }
      add_points();
      for (const std::size_t end = known.size(); removed_done < end && local(front); ++removed_done)
        for (const Cell c : star(known[removed_done]))
          if (!c->info().kept) {
            c->info().kept = 1;
            c->info().local = 0;
            front.push_back(c);
          }
    }
    // The points looked around in both steps have all their finite cells in
    // the front (filled): fill_to_ball knows their boundary triangles are
    // their convex hull triangles (none inside the hull), which form a disk.
    for (std::size_t k = 0; k < std::min(kept_done, removed_done); ++k) {
      const auto id = static_cast<std::size_t>(known[k]->info());
      inner[id] = star_hull[static_cast<std::size_t>(star_slot[id])];
      inner_points.push_back(static_cast<int>(id));
    }
    for (const Vertex v : known) fill_vertex[static_cast<std::size_t>(v->info())] = -1;
    // The skin: layers of cells across a face from the rings, kept and
    // removed (these filled) alike.
    std::size_t from = 0;
    for (std::size_t layer = 0; layer < kSkinLayers && local(front); ++layer) {
      const std::size_t to = front.size();
      for (std::size_t i = from; i < to; ++i)
        for (int k = 0; k < 4; ++k) {
          const Cell n = front[i]->neighbor(k);
          if (dt.is_infinite(n) || n->info().local >= 0) continue;
          n->info().local = 0;
          n->info().kept = 1;
          front.push_back(n);
        }
      from = to;
    }
    enclosed = from;  // each layer took in every finite cell across the faces of those before
    for (const Cell c : front) c->info().local = -1;
    for (const Cell c : rest) c->info().local = -1;
    front.insert(front.end(), rest.begin(), rest.end());
    return front;
  }

  // Fill, check, constrict again (see the class comment).
  void repair(const std::vector<Vertex>& fresh, BatchStats& s) {
    carry_stars_over();
    std::vector<Cell> front, rest;
    new_cells(fresh, front, rest);
    std::size_t enclosed = 0;
    std::vector<Cell> region = with_margin(std::move(front), rest, enclosed);
    FillParts parts;
    const bool ball = fill_to_ball(region, parts, enclosed);
    const auto forget_inner = [&] {
      for (const int id : inner_points) inner[static_cast<std::size_t>(id)] = -1;
      inner_points.clear();
    };
    if (ball) {
      // Each connected part of the fill is constricted on its own, so a part
      // that locks releases rings of kept cells around itself only, and the
      // others stop where their points are reached. Parts are numbered in
      // the order of their first cells.
      std::vector<int> label(parts.vertices.size(), -1);
      std::vector<std::vector<Cell>> pieces;
      std::vector<std::vector<Vertex>> piece_vertices;
      for (std::size_t i = 0; i < region.size(); ++i) {  // the check saw every cell (ball)
        const Cell c = region[i];
        int& l = label[static_cast<std::size_t>(parts.find(parts.cell_point[i]))];
        if (l < 0) {
          l = static_cast<int>(pieces.size());
          pieces.emplace_back();
        }
        pieces[static_cast<std::size_t>(l)].push_back(c);
      }
      // Each part's points in the order of their first cells: a point's
      // cells are all in its part, so the fill's order restricted to it.
      piece_vertices.resize(pieces.size());
      for (std::size_t k = 0; k < parts.vertices.size(); ++k)
        piece_vertices[static_cast<std::size_t>(label[static_cast<std::size_t>(parts.find(static_cast<int>(k)))])].push_back(
            parts.vertices[k]);
      forget(parts);
      for (std::size_t p = 0; p < pieces.size(); ++p) {
        std::vector<Cell>& piece = pieces[p];
        for (int ring = 0;; ++ring) {
          // The last ring keeps its result even if it locked: the points it
          // could not reach stay pending (augmentation brings them on, §5.4).
          // A ring may take in cells of a later part: that part's own
          // constriction then starts from what this one left.
          const bool last = ring == kUnfreezeRings;
          if (constrict_region(piece, true, last, s, static_cast<int>(p), ring == 0 ? &piece_vertices[p] : nullptr) || last) {
            s.rings = std::max(s.rings, ring);
            break;
          }
          grow(piece, [](Cell c) { return c->info().kept != 0; });
        }
      }
      forget_inner();
      // The joined points' cone triangles too (some of them re-decided in a front).
      s.faces_changed = std::min(patch_size() + joined_faces, static_cast<std::size_t>(corners / 3));
      return;
    }
    forget(parts);
    forget_inner();
    s.wider_repair = true;
    ++wider;
    constrict_all(s);
    s.faces_changed = 2 * points.size() - 4;  // the whole boundary (F = 2V − 4) was re-decided
  }
};

IncrementalConstriction::IncrementalConstriction(const ReconstructionOptions& options, int margin, double local_share)
    : state_(std::make_unique<State>()) {
  if (margin < 0) throw InvalidInput("the margin of the incremental constriction must be at least 0, got " + std::to_string(margin));
  if (!(local_share > 0.0 && local_share <= 1.0))
    throw InvalidInput("the local share of the incremental constriction must be in (0, 1], got " + std::to_string(local_share));
  if (options.voronoi_skeleton) throw InvalidInput("the incremental constriction has no Voronoi skeleton method");
  if (options.constriction.keep.rows() > 0)
    throw InvalidInput("the incremental constriction does not support faces to keep (§5.7)");
  state_->options = options;
  state_->constriction = constriction_options(options);
  state_->margin = margin;
  state_->local_share = local_share;
}

IncrementalConstriction::~IncrementalConstriction() = default;
IncrementalConstriction::IncrementalConstriction(IncrementalConstriction&&) noexcept = default;
IncrementalConstriction& IncrementalConstriction::operator=(IncrementalConstriction&&) noexcept = default;

BatchStats IncrementalConstriction::add_batch(const Eigen::MatrixX3d& batch, const std::optional<Eigen::Vector3d>& viewpoint) {
  const auto start = std::chrono::steady_clock::now();
  if (!batch.allFinite()) throw InvalidInput("batch points contain NaN or infinite coordinates");
  if (viewpoint && !viewpoint->allFinite()) throw InvalidInput("the batch's viewpoint has NaN or infinite coordinates");
  State& s = *state_;
  s.batch_viewpoint = -1;
  if (viewpoint) {
    s.batch_viewpoint = static_cast<int>(s.viewpoints.size());
    s.viewpoints.push_back(*viewpoint);
  }
  BatchStats stats;
  stats.points_received = static_cast<std::size_t>(batch.rows());
  ++s.batch;
  s.joined_faces = 0;
  const std::vector<Vertex> fresh = s.insert(batch, stats.points_joined);
  stats.points_inserted = fresh.size();
  if (s.dt.dimension() == 3) {
    if (!s.started) {
      s.started = true;
      s.constrict_all(stats);
      stats.faces_changed = 2 * s.points.size() - 4;
    } else if (!fresh.empty()) {
      s.repair(fresh, stats);
    }
  }
  stats.points_so_far = s.points.size();
  stats.pending = s.pending_count;
  stats.all_on_boundary = s.started && s.pending_count == 0;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

SurfaceReconstruction IncrementalConstriction::surface() const {
  State& s = *state_;
  SurfaceReconstruction out;
  const auto n = static_cast<Eigen::Index>(s.points.size());
  out.mesh.vertices.positions.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) out.mesh.vertices.positions.row(i) = s.points[static_cast<std::size_t>(i)].transpose();
  out.source = s.source;
  out.statistics.input_points = s.received;
  out.statistics.duplicates_merged = s.duplicates;
  if (!s.started) {
    out.mesh.faces.resize(0, 3);
    for (Eigen::Index i = 0; i < n; ++i) out.statistics.interior_vertices.push_back(static_cast<int>(i));
    return out;
  }
  // The whole triangulation as a complex over all points (their own numbers).
  DelaunayComplex<3> dt;
  dt.points = out.mesh.vertices.positions;
  std::vector<Cell> cells;
  for (const Cell c : s.dt.finite_cell_handles()) {
    c->info().local = static_cast<int>(cells.size());
    cells.push_back(c);
  }
  dt.cells.resize(static_cast<Eigen::Index>(cells.size()), 4);
  dt.neighbors.resize(dt.cells.rows(), 4);
  std::vector<char> kept(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    kept[i] = cells[i]->info().kept;
    for (int k = 0; k < 4; ++k) {
      dt.cells(static_cast<Eigen::Index>(i), k) = cells[i]->vertex(k)->info();
      const Cell nb = cells[i]->neighbor(k);
      dt.neighbors(static_cast<Eigen::Index>(i), k) = s.dt.is_infinite(nb) ? -1 : nb->info().local;
    }
  }
  for (const Cell c : cells) c->info().local = -1;
  Constriction<3> c = pruned_boundary(dt, std::move(kept));
  finish_surface(dt, c, s.options, out);
  return out;
}

TriangleMesh IncrementalConstriction::boundary() const { return surface().mesh; }

Eigen::Index IncrementalConstriction::point_count() const { return static_cast<Eigen::Index>(state_->points.size()); }

Eigen::Index IncrementalConstriction::boundary_face_count() const {
  return state_->started ? state_->corners / 3 : 0;
}

std::size_t IncrementalConstriction::wider_repairs() const { return state_->wider; }

}  // namespace scanstation
