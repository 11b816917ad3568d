// From scattered points to a closed boundary: duplicate merging, Delaunay
// triangulation, constriction (thesis Chapter 5), and the result as a mesh or
// polygon with what a report needs.
#pragma once

#include "core/polygon.h"
#include "core/triangle_mesh.h"
#include "reconstruct/augmentation.h"
#include "reconstruct/boundary_flips.h"
#include "reconstruct/constriction.h"
#include "reconstruct/gap_carving.h"
#include "reconstruct/line_of_sight.h"
#include "reconstruct/unfold_boundary.h"
#include "reconstruct/voronoi_skeleton.h"
#include "reconstruct/web_carving.h"

#include <future>
#include <memory>
#include <optional>
#include <vector>

namespace scanstation {

class PointTree;

/// γ-guided constriction (a scanstation extension of §5.7): Delaunay faces
/// whose two empty Delaunay balls are both wide — the face is in
/// γ([c0,1],[c1,1]) read from its two γ-indicators — are kept like
/// user-given faces, so constriction does not cut through what the γ-graph
/// already shows as the object's outside (§3.4: well-chosen γ-parameters
/// reveal the external structure).
struct GuideOptions {
  double c1 = 0.5;  ///< the wider ball must reach at least this γ-value
  double c0 = 0.0;  ///< and the narrower one at least this
};

struct ReconstructionOptions {
  ConstrictionOptions constriction;
  /// Set: the shortest Voronoi skeleton (§4.3.4) instead of constriction,
  /// the comparison baseline of §5.6 (the constriction options other than
  /// the progress callback do not apply; augmentation and flips do).
  std::optional<VoronoiSkeletonOptions> voronoi_skeleton;
  /// 3D: keep the faces the γ-graph marks as outside; nullopt: plain thesis constriction.
  std::optional<GuideOptions> guide = GuideOptions{};
  /// When constriction locks, carve on with triangles (2D) or tetrahedra (3D)
  /// of γ([-1,1],[c0,1]), c0 < 0 (§5.4); off: keep the locked boundary.
  bool augment = true;
  AugmentationOptions augmentation;
  /// 3D: right after constriction, Delaunay flips that add or remove one
  /// Delaunay cell each (reconstruct/boundary_flips.h, flip_delaunay_cells):
  /// where the constricted boundary is nearly flat, the diagonal of a quad
  /// that is locally Delaunay on the surface (a convex surface ends as its
  /// convex hull otherwise: CGAL's ellipe0.003 recalls 0.753 of its true
  /// triangles without, 0.999 with). No geometric test is needed, the kept
  /// cells stay a triangulation of the solid (§5.8), and each flip costs a
  /// few cell lookups (docs/design.md, step 6).
  bool cell_flips = true;
  /// 3D: once every point is on the boundary, flip edges that lower the
  /// surface area (O'Rourke's flips, §4.3.2), and with area_then_delaunay
  /// (default) then towards a Delaunay surface where it is nearly flat
  /// (more true triangles on real meshes; on a random sample of a convex
  /// surface the cell flips have made them all already, so it costs
  /// nothing there); nullopt: keep constriction's triangles as they are.
  std::optional<FlipCriterion> flips = FlipCriterion::area_then_delaunay;
  /// 3D: then re-triangulate flat the places where the surface folds back on
  /// itself (reconstruct/unfold_boundary.h).
  bool unfold = true;
  /// 3D: where the points were seen from (indices into the input points):
  /// the Delaunay cells these lines of sight cross are carved first
  /// (reconstruct/line_of_sight.h, ConstrictionOptions::carve_first).
  std::vector<SightLine> sight_lines;
  /// 3D: carve first the cells the outside reaches through faces far wider
  /// than the sampling around them (gaps between parts), after the lines of
  /// sight (reconstruct/gap_carving.h); nullopt (default): not. Not done by
  /// the incremental repair (docs/design.md, "Gap carving").
  std::optional<GapOptions> gaps;
  /// 3D: right after constriction, remove the webs, sheets of kept cells
  /// spanning a gap between two parts, each as a whole where the boundary
  /// stays a sphere through every point (reconstruct/web_carving.h; done by
  /// the incremental repair's final surface too); nullopt: keep them.
  std::optional<WebOptions> webs = WebOptions{};
};

struct BoundaryStatistics {
  Eigen::Index input_points = 0;
  Eigen::Index duplicates_merged = 0;     ///< input points equal to an earlier one, dropped
  Eigen::Index boundary_vertices = 0;
  std::vector<int> interior_vertices;     ///< distinct points not reached (indices into the distinct points)
  bool all_on_boundary = false;
  std::size_t delaunay_cells = 0;
  std::size_t removed_cells = 0;
  double enclosed_measure = 0.0;          ///< area (2D) or volume (3D) enclosed by the boundary
  std::optional<double> c0_used;          ///< the γ([-1,1],[c0,1]) level augmentation reached, if it ran
  std::size_t carved = 0;                 ///< tetrahedra carved by augmentation
  std::size_t kept_faces_on_boundary = 0; ///< of the faces asked to stay (§5.7), how many are on the boundary
  std::size_t cell_flips = 0;             ///< Delaunay flips that added or removed a cell (right after constriction)
  std::size_t flips = 0;                  ///< edge flips made after constriction
  std::size_t folds = 0;                  ///< fold edges (faces turning by more than 120°) after the flips
  std::size_t folds_left = 0;             ///< of them, left after unfolding
  std::size_t unfolded = 0;               ///< fold patches re-triangulated flat
  std::size_t guide_faces = 0;            ///< faces kept by γ-guided constriction
  std::size_t sight_line_cells = 0;       ///< Delaunay cells crossed by the lines of sight
  std::size_t gap_cells = 0;              ///< Delaunay cells found in gaps, carved first
  std::size_t web_cells = 0;              ///< kept Delaunay cells removed with webs after constriction
  double flip_seconds = 0.0;
  double unfold_seconds = 0.0;
  double delaunay_seconds = 0.0;
  double constriction_seconds = 0.0;
};

/// A closed polyhedron through the points.
/// mesh       vertices: the distinct input points in input order (first
///            occurrences, bit-identical values); faces: the boundary,
///            counter-clockwise seen from outside
/// interior   #T by 4 kept tetrahedra (indices into mesh vertices): a
///            tetrahedralization of the enclosed solid (§5.8; cell flips
///            keep it one); empty when augmentation carved or flips changed
///            the boundary (their tetrahedra overlap Delaunay cells)
/// source     #V: the input row each mesh vertex came from
/// constricted  #C by 3: the boundary as constriction, web carving and the
///            cell flips left it, before augmentation, edge flips and
///            unfolding: facets of the Delaunay tetrahedralization (mesh
///            vertex indices), which meet one another only in shared
///            vertices and edges
struct SurfaceReconstruction {
  TriangleMesh mesh;
  std::vector<Eigen::Index> source;
  Eigen::MatrixX4i interior;
  Eigen::MatrixX3i constricted;
  BoundaryStatistics statistics;
};

/// Per face of r.mesh, 1 when it is one of r.constricted (a Delaunay facet):
/// a check for self-intersections need not pair two of them
/// (core/self_intersections.h).
std::vector<char> delaunay_facets(const SurfaceReconstruction& r);

/// A simple polygon through the planar points.
/// points    the distinct input points in input order
/// polygon   the boundary, counter-clockwise; `order` its vertices as indices
///           into `points`
/// interior  #T by 3 kept triangles (indices into `points`); empty when
///           augmentation carved
/// delaunay  all Delaunay triangles, kept and removed (for pictures)
/// source    #points: the input row each distinct point came from
struct CurveReconstruction {
  Eigen::MatrixX2d points;
  std::vector<Eigen::Index> source;
  Polygon2 polygon;
  std::vector<int> order;
  Eigen::MatrixX3i interior;
  DelaunayComplex<2>::Cells delaunay;
  BoundaryStatistics statistics;
};

/// The constriction options of a reconstruction: options.constriction with
/// the γ-guide of options.guide.
ConstrictionOptions constriction_options(const ReconstructionOptions& options);

/// What the stages after constriction index over a complex alone: the cells
/// around each point (web carving, augmentation's neighbours, the flips)
/// and a tree over its points (augmentation, the flips' exact tests).
struct ComplexIndexes {
  CellsAround around;
  std::shared_ptr<const PointTree> points;
};

/// The stages after constriction of a 3D Delaunay complex, shared by
/// reconstruct_surface and the incremental constriction: augmentation (§5.4)
/// when c left points interior and options.augment is on, the flips of
/// options.flips, the kept tetrahedra and the statistics. out.mesh.vertices
/// must hold the points (dt.points up to scale); fills out.mesh.faces,
/// out.interior and out.statistics (except the input counts and Delaunay time).
/// indexes optional: the cells around each point and a tree over dt.points,
/// being built on another thread (reconstruct_surface starts them while
/// constriction runs); else they are built when first needed.
void finish_surface(const DelaunayComplex<3>& dt, Constriction<3>& c, const ReconstructionOptions& options,
                    SurfaceReconstruction& out, std::future<ComplexIndexes>* indexes = nullptr);

/// What `scanstation reconstruct` does with 3D points: the defaults with
/// ConstrictionCriterion::area_change_and_gamma, which recovers the most true
/// triangles on real meshes (the defaults keep the thesis' γ-indicator).
ReconstructionOptions surface_defaults();

/// Kept faces (options.constriction.keep) index the input points; duplicates
/// of a point stand for its first occurrence.
/// Throws InvalidInput for fewer than 4 (3) distinct points, or points all in
/// one plane (on one line).
SurfaceReconstruction reconstruct_surface(const Eigen::MatrixX3d& points, const ReconstructionOptions& options = {});
CurveReconstruction reconstruct_curve(const Eigen::MatrixX2d& points, const ReconstructionOptions& options = {});

}  // namespace scanstation
