#include "reconstruct/boundary_reconstruction.h"

#include "core/errors.h"
#include "core/mesh_measures.h"
#include "core/unique_points.h"
#include "core/unit_scale.h"
#include "reconstruct/boundary_surface.h"
#include "reconstruct/cell_blocks.h"
#include "reconstruct/triangle_set.h"

#include <Eigen/Geometry>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <future>
#include <limits>
#include <string>
#include <thread>

namespace scanstation {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Kept faces given by input indices, renumbered to the distinct points.
// map as delaunay_complex gives it: when empty, the inverse of first.
ReconstructionOptions renumbered(const ReconstructionOptions& options, std::vector<Eigen::Index>& map,
                                 const std::vector<Eigen::Index>& first) {
  if (options.voronoi_skeleton && options.constriction.keep.rows() > 0)
    throw InvalidInput("faces to keep (§5.7) apply to constriction, not to the Voronoi skeleton method");
  if (map.empty() && (options.constriction.keep.rows() > 0 || !options.sight_lines.empty())) {
    map.resize(first.size());
    for (std::size_t k = 0; k < first.size(); ++k) map[static_cast<std::size_t>(first[k])] = static_cast<Eigen::Index>(k);
  }
  ReconstructionOptions out = options;
  for (Eigen::Index k = 0; k < out.constriction.keep.rows(); ++k)
    for (Eigen::Index i = 0; i < out.constriction.keep.cols(); ++i) {
      const int v = out.constriction.keep(k, i);
      if (v < 0 || static_cast<std::size_t>(v) >= map.size())
        throw InvalidInput("kept face " + std::to_string(k) + ": point index " + std::to_string(v) + " out of range [0, " +
                           std::to_string(map.size()) + ")");
      out.constriction.keep(k, i) = static_cast<int>(map[static_cast<std::size_t>(v)]);
    }
  if (out.constriction.keep.cols() == 3) out.augmentation.keep = out.constriction.keep;
  for (SightLine& line : out.sight_lines) {
    if (line.point < 0 || static_cast<std::size_t>(line.point) >= map.size())
      throw InvalidInput("sight line: point index " + std::to_string(line.point) + " out of range [0, " +
                         std::to_string(map.size()) + ")");
    line.point = static_cast<int>(map[static_cast<std::size_t>(line.point)]);
  }
  return out;
}

// A template, not a const MatrixXd&: an N by 2 or 3 matrix would be copied
// into a dynamic one first (at 1M points 50 ms of a 1.4 s 2D reconstruction).
template <typename Points>
void require_finite(const Points& P) {
  if (!P.allFinite()) throw InvalidInput("points contain NaN or infinite coordinates");
}

// The Delaunay triangulation of the distinct points, scaled by `scale`, its
// points numbered in spatial order (CGAL's vertex storage order: cells close
// together read points close together in memory), with
// first  per point of the complex, its input row (the first occurrence)
// map    per input row, the point of the complex equal to it (2D: empty
//        when no row repeats, see delaunay_complex)
// output per point of the complex, its number among the distinct points in
//        input order, as unique_points numbers them (empty: the same)
// 3D: merging duplicates (a hash pass) runs on the other core while CGAL
// triangulates all rows; its insertion skips a repeated point, so that is
// the triangulation of the distinct points.
DelaunayComplex<3> distinct_delaunay(const Eigen::MatrixX3d& points, double scale, std::vector<Eigen::Index>& first,
                                     std::vector<Eigen::Index>& map, std::vector<int>& output) {
  std::vector<Eigen::Index> first_in_order, map_in_order;
  std::thread merge([&] { unique_points(points, first_in_order, map_in_order); });
  DelaunayComplex<3> dt;
  std::vector<Eigen::Index> rows;
  std::exception_ptr failure;
  try {
    dt = delaunay_complex(points, rows, scale);
  } catch (...) {
    failure = std::current_exception();
  }
  merge.join();
  const auto distinct = static_cast<Eigen::Index>(first_in_order.size());
  if (distinct < 4)
    throw InvalidInput("need at least 4 distinct points for a closed polyhedron, got " + std::to_string(distinct));
  if (failure) std::rethrow_exception(failure);
  // CGAL merges exactly the values unique_points merges: one vertex each.
  if (static_cast<Eigen::Index>(rows.size()) != distinct)
    throw TopologyError("the triangulation has " + std::to_string(rows.size()) + " vertices for " +
                        std::to_string(distinct) + " distinct points (please report this input)");
  output.resize(rows.size());
  std::vector<Eigen::Index> vertex_of(rows.size());  // distinct point (input order) → point of the complex
  first.resize(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const Eigen::Index d = map_in_order[static_cast<std::size_t>(rows[k])];
    output[k] = static_cast<int>(d);
    vertex_of[static_cast<std::size_t>(d)] = static_cast<Eigen::Index>(k);
    first[k] = first_in_order[static_cast<std::size_t>(d)];
  }
  map.resize(map_in_order.size());
  for (std::size_t i = 0; i < map.size(); ++i) map[i] = vertex_of[static_cast<std::size_t>(map_in_order[i])];
  // The copy CGAL kept may differ from the first occurrence in the sign of
  // a zero.
  if (distinct < points.rows())
    for (std::size_t k = 0; k < rows.size(); ++k) dt.points.row(static_cast<Eigen::Index>(k)) = points.row(first[k]) * scale;
  return dt;
}

// 2D: CGAL's insertion meets each repeated point at its vertex, which is all
// the duplicate merging needed (no second pass over the points); the
// distinct points keep the complex's order in the output.
DelaunayComplex<2> distinct_delaunay(const Eigen::MatrixX2d& points, double scale, std::vector<Eigen::Index>& first,
                                     std::vector<Eigen::Index>& map, std::vector<int>& output) {
  output.clear();
  return delaunay_complex(points, first, map, scale);
}

template <int D>
struct Triangulated {
  Eigen::Matrix<double, Eigen::Dynamic, D> original;  // distinct points, input values, in the complex's order
  DelaunayComplex<D> dt;                              // over the distinct points, unit-scaled
  std::vector<int> output;                            // see distinct_delaunay
};

template <int D>
Triangulated<D> triangulate_distinct(const Eigen::Matrix<double, Eigen::Dynamic, D>& points, BoundaryStatistics& s,
                                     std::vector<Eigen::Index>& map, std::vector<Eigen::Index>& first) {
  require_finite(points);
  s.input_points = points.rows();
  const auto start = std::chrono::steady_clock::now();
  Triangulated<D> out;
  const double scale = unit_scale(points);
  out.dt = distinct_delaunay(points, scale, first, map, out.output);
  s.duplicates_merged = points.rows() - static_cast<Eigen::Index>(first.size());
  // The power of two undoes exactly. Assigned as an expression: no
  // temporary (in 2D the complex's points are row by row, the output's not).
  out.original = out.dt.points / scale;
  s.delaunay_seconds = seconds_since(start);
  return out;
}

// From the complex's numbering of the points to the output's (distinct
// points in input order): vertices, faces, tetrahedra, interior points.
void to_output_numbering(const std::vector<int>& output, SurfaceReconstruction& out) {
  const auto renumber = [&](auto& indices) {
    for (Eigen::Index i = 0; i < indices.size(); ++i)
      indices.data()[i] = output[static_cast<std::size_t>(indices.data()[i])];
  };
  renumber(out.mesh.faces);
  renumber(out.interior);
  renumber(out.constricted);
  for (int& v : out.statistics.interior_vertices) v = output[static_cast<std::size_t>(v)];
  std::sort(out.statistics.interior_vertices.begin(), out.statistics.interior_vertices.end());
  Eigen::MatrixX3d positions(out.mesh.vertices.positions.rows(), 3);
  std::vector<Eigen::Index> source(out.source.size());
  for (std::size_t k = 0; k < output.size(); ++k) {
    positions.row(output[k]) = out.mesh.vertices.positions.row(static_cast<Eigen::Index>(k));
    source[static_cast<std::size_t>(output[k])] = out.source[k];
  }
  out.mesh.vertices.positions = std::move(positions);
  out.source = std::move(source);
}

// The kept cells' rows of dt.cells, in cell order: counted and copied by
// blocks of cells on all cores (a triangulation of the inside, §5.8).
template <int D>
Eigen::Matrix<int, Eigen::Dynamic, D + 1> kept_cells(const DelaunayComplex<D>& dt, const std::vector<char>& kept) {
  const std::size_t blocks = (kept.size() + kCellBlock - 1) / kCellBlock;
  const std::vector<std::size_t> offset = block_offsets(blocks, [&](std::size_t b) {
    const auto first = kept.begin() + static_cast<std::ptrdiff_t>(b * kCellBlock);
    return static_cast<std::size_t>(std::count_if(
        first, first + static_cast<std::ptrdiff_t>(std::min(kCellBlock, kept.size() - b * kCellBlock)), [](char k) { return k != 0; }));
  });
  Eigen::Matrix<int, Eigen::Dynamic, D + 1> out(static_cast<Eigen::Index>(offset.back()), D + 1);
  for_each_block(blocks, [&](std::size_t b) {
    auto row = static_cast<Eigen::Index>(offset[b]);
    for (std::size_t k = b * kCellBlock; k < std::min(kept.size(), (b + 1) * kCellBlock); ++k)
      if (kept[k]) out.row(row++) = dt.cells.row(static_cast<Eigen::Index>(k));
  });
  return out;
}

template <int D>
void fill_statistics(BoundaryStatistics& s, const DelaunayComplex<D>& dt, Constriction<D>& c) {
  s.delaunay_cells = static_cast<std::size_t>(dt.cells.rows());
  s.removed_cells = c.removed_cells;
  s.interior_vertices = std::move(c.interior_vertices);
  s.all_on_boundary = c.all_on_boundary;
  s.boundary_vertices = dt.points.rows() - static_cast<Eigen::Index>(s.interior_vertices.size());
}

// How many rows of `wanted` (#K by D vertex indices) are faces of
// `boundary` (#B by D), as unordered tuples.
template <typename Faces>
std::size_t faces_on(const Eigen::MatrixXi& wanted, const Faces& boundary) {
  if (wanted.rows() == 0) return 0;
  const auto sorted = [](Eigen::VectorXi row) {
    std::sort(row.data(), row.data() + row.size());
    return std::vector<int>(row.data(), row.data() + row.size());
  };
  std::vector<std::vector<int>> have;
  for (Eigen::Index f = 0; f < boundary.rows(); ++f) have.push_back(sorted(boundary.row(f).transpose()));
  std::sort(have.begin(), have.end());
  std::size_t count = 0;
  for (Eigen::Index k = 0; k < wanted.rows(); ++k)
    count += std::binary_search(have.begin(), have.end(), sorted(wanted.row(k).transpose()));
  return count;
}

// The cells constriction removes first: those the lines of sight cross,
// nearest the viewpoints first, then those in gaps, nearest the hull first.
std::vector<int> carve_first(const DelaunayComplex<3>& dt, const Eigen::MatrixX3d& original,
                             const ReconstructionOptions& options, BoundaryStatistics& s) {
  const auto count = [](const std::vector<int>& ranks) {
    return static_cast<std::size_t>(std::count_if(ranks.begin(), ranks.end(), [](int rank) { return rank >= 0; }));
  };
  std::vector<int> seen, gaps;
  if (!options.sight_lines.empty()) seen = line_of_sight_depths(dt, original, options.sight_lines);
  if (options.gaps) gaps = gap_depths(dt, *options.gaps);
  s.sight_line_cells = count(seen);
  std::vector<int> ranks = carve_first_then(std::move(seen), gaps);
  s.gap_cells = count(ranks) - s.sight_line_cells;
  return ranks;
}

}  // namespace

ConstrictionOptions constriction_options(const ReconstructionOptions& options) {
  ConstrictionOptions out = options.constriction;
  if (options.guide) {
    out.guide_c1 = options.guide->c1;
    out.guide_c0 = options.guide->c0;
  }
  return out;
}

void finish_surface(const DelaunayComplex<3>& dt, Constriction<3>& c, const ReconstructionOptions& options,
                    SurfaceReconstruction& out, std::future<ComplexIndexes>* indexes) {
  BoundaryStatistics& s = out.statistics;
  s.guide_faces = c.guide_faces;
  // Both before augmentation: they need a boundary of cells. Every cell left
  // outside counts as removed, those these passes took out too. The cell
  // flips read the kept flags alone, so the boundary is listed again once,
  // after both.
  bool changed = false;
  std::optional<CellsAround> around;  // given, or indexed by the first step that needs it, then shared
  std::shared_ptr<const PointTree> tree;
  if (indexes && indexes->valid()) {
    ComplexIndexes ready = indexes->get();
    around.emplace(std::move(ready.around));
    tree = std::move(ready.points);
  }
  if (options.webs) {
    const auto start = std::chrono::steady_clock::now();
    s.web_cells = carve_webs(dt, c.kept, c.boundary, options.constriction.keep, *options.webs, &around);
    changed = s.web_cells > 0;
    s.constriction_seconds += seconds_since(start);
  }
  const auto start = std::chrono::steady_clock::now();
  if (options.cell_flips) {
    s.cell_flips = flip_delaunay_cells(dt, c.kept, options.constriction.keep);
    changed = changed || s.cell_flips > 0;
  }
  if (changed) {
    Constriction<3> renewed = pruned_boundary(dt, std::move(c.kept));
    renewed.guide_faces = c.guide_faces;
    c = std::move(renewed);
  }
  s.flip_seconds = seconds_since(start);
  out.mesh.faces = c.boundary;
  // The surface's spatial index, built by the first step that needs one
  // (augmentation, the flips) and handed on to the next (the flips,
  // unfolding).
  std::optional<BoundarySurface> surface;
  if (!c.all_on_boundary && options.augment) {
    const auto start = std::chrono::steady_clock::now();
    const Augmentation a = augment_constriction(dt.points, PointNeighbours(dt, around), out.mesh.faces, c.interior_vertices,
                                                options.augmentation, &surface, tree);
    s.constriction_seconds += seconds_since(start);
    s.c0_used = a.c0_used;
    s.carved = a.carved;
    c.all_on_boundary = c.interior_vertices.empty();
  }
  if (options.flips) {
    const auto start = std::chrono::steady_clock::now();
    s.flips = flip_boundary(dt.points, out.mesh.faces, *options.flips, options.constriction.keep, 1e-3, &dt, &surface,
                            &around, tree);
    s.flip_seconds += seconds_since(start);
  }
  around.reset();  // unfolding needs neither: the peak memory is here on real meshes
  tree.reset();
  if (options.unfold) {
    const auto start = std::chrono::steady_clock::now();
    const UnfoldStatistics u =
        surface ? unfold_boundary(*surface, dt.points, out.mesh.faces, options.constriction.keep)
                : unfold_boundary(dt.points, out.mesh.faces, options.constriction.keep);
    s.folds = u.folds_before;
    s.folds_left = u.folds_after;
    s.unfolded = u.retriangulated;
    s.unfold_seconds = seconds_since(start);
  }
  // Carved, flipped or unfolded triangles are no faces of the kept cells:
  // then no interior triangulation (not even made, as on most real meshes).
  if (s.carved == 0 && s.flips == 0 && s.unfolded == 0) out.interior = kept_cells(dt, c.kept);
  s.enclosed_measure = enclosed_volume(out.mesh.vertices.positions, out.mesh.faces);
  fill_statistics(s, dt, c);
  s.kept_faces_on_boundary = faces_on(options.constriction.keep, out.mesh.faces);
  out.constricted = std::move(c.boundary);
}

std::vector<char> delaunay_facets(const SurfaceReconstruction& r) {
  const Eigen::MatrixX3i& faces = r.mesh.faces;
  std::vector<char> facet(static_cast<std::size_t>(faces.rows()), 1);
  if (faces.rows() == r.constricted.rows() && faces == r.constricted) return facet;  // no pass after constriction changed it
  const TriangleSet constricted(Eigen::MatrixXi(r.constricted));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    facet[static_cast<std::size_t>(f)] = constricted.contains(faces(f, 0), faces(f, 1), faces(f, 2));
  return facet;
}

ReconstructionOptions surface_defaults() {
  ReconstructionOptions options;
  options.constriction.criterion = ConstrictionCriterion::area_change_and_gamma;
  return options;
}

SurfaceReconstruction reconstruct_surface(const Eigen::MatrixX3d& points, const ReconstructionOptions& given) {
  SurfaceReconstruction out;
  BoundaryStatistics& s = out.statistics;
  std::vector<Eigen::Index> map;
  Triangulated<3> triangulated = triangulate_distinct<3>(points, s, map, out.source);
  const DelaunayComplex<3>& dt = triangulated.dt;
  const ReconstructionOptions options = renumbered(given, map, out.source);

  const auto start = std::chrono::steady_clock::now();
  // The indexes the stages after constriction need, on the other core while
  // constriction runs on this one (alone: TBB's workers would take turns
  // with constriction); with one core, when first needed. Declared after
  // the complex: its destructor waits.
  std::future<ComplexIndexes> indexes;
  if ((options.webs || options.augment || options.flips) && std::thread::hardware_concurrency() > 1)
    indexes = std::async(std::launch::async, [&dt] {
      tbb::task_arena one_core(1);
      return one_core.execute([&] { return ComplexIndexes{CellsAround(dt), std::make_shared<const PointTree>(dt.points)}; });
    });
  ConstrictionOptions constriction = constriction_options(options);
  constriction.carve_first = carve_first(dt, triangulated.original, options, s);
  Constriction<3> c = options.voronoi_skeleton ? voronoi_skeleton(dt, *options.voronoi_skeleton)
                                               : constrict(dt, constriction);
  s.constriction_seconds = seconds_since(start);
  out.mesh.vertices.positions = std::move(triangulated.original);
  finish_surface(dt, c, options, out, &indexes);
  to_output_numbering(triangulated.output, out);
  return out;
}

CurveReconstruction reconstruct_curve(const Eigen::MatrixX2d& points, const ReconstructionOptions& given) {
  CurveReconstruction out;
  BoundaryStatistics& s = out.statistics;
  std::vector<Eigen::Index> map;
  Triangulated<2> triangulated = triangulate_distinct<2>(points, s, map, out.source);
  out.points = std::move(triangulated.original);
  const DelaunayComplex<2>& dt = triangulated.dt;
  const ReconstructionOptions options = renumbered(given, map, out.source);

  auto start = std::chrono::steady_clock::now();
  Constriction<2> c =
      options.voronoi_skeleton ? voronoi_skeleton(dt, *options.voronoi_skeleton) : constrict(dt, options.constriction);
  s.constriction_seconds = seconds_since(start);
  if (!c.all_on_boundary && options.augment) {
    start = std::chrono::steady_clock::now();
    const Augmentation a = augment_constriction(Eigen::MatrixX2d(dt.points), PointNeighbours(dt), c.boundary,
                                                c.interior_vertices, options.augmentation);
    s.constriction_seconds += seconds_since(start);
    s.c0_used = a.c0_used;
    s.carved = a.carved;
    c.all_on_boundary = c.interior_vertices.empty();
  }

  // The boundary edges chain into one cycle: each boundary vertex has exactly
  // one outgoing edge.
  std::vector<int> next(static_cast<std::size_t>(out.points.rows()), -1);
  for (Eigen::Index e = 0; e < c.boundary.rows(); ++e) next[static_cast<std::size_t>(c.boundary(e, 0))] = c.boundary(e, 1);
  const int start_vertex = c.boundary(0, 0);
  int v = start_vertex;
  out.order.reserve(static_cast<std::size_t>(c.boundary.rows()));
  do {
    out.order.push_back(v);
    v = next[static_cast<std::size_t>(v)];
  } while (v != start_vertex && v >= 0 && out.order.size() <= static_cast<std::size_t>(c.boundary.rows()));
  if (v != start_vertex || out.order.size() != static_cast<std::size_t>(c.boundary.rows()))
    throw TopologyError("constriction left a boundary that is not one simple cycle (please report this input)");
  // The polygon starts at its point of the smallest input row, whatever the
  // internal numbering (spatial, see delaunay_complex).
  std::rotate(out.order.begin(),
              std::min_element(out.order.begin(), out.order.end(),
                               [&](int a, int b) {
                                 return out.source[static_cast<std::size_t>(a)] < out.source[static_cast<std::size_t>(b)];
                               }),
              out.order.end());
  out.polygon.vertices.resize(static_cast<Eigen::Index>(out.order.size()), 2);
  for (std::size_t k = 0; k < out.order.size(); ++k)
    out.polygon.vertices.row(static_cast<Eigen::Index>(k)) = out.points.row(out.order[k]);

  if (s.carved == 0) out.interior = kept_cells(dt, c.kept);  // carved triangles overlap Delaunay cells: then none
  s.enclosed_measure = twice_signed_area(out.polygon) / 2.0;
  fill_statistics(s, dt, c);
  out.delaunay = std::move(triangulated.dt.cells);  // dt is not used after this
  s.kept_faces_on_boundary = faces_on(options.constriction.keep, c.boundary);
  return out;
}

}  // namespace scanstation
