// Constriction of the Delaunay triangulation γ([-1,1],[0,1]) into a closed
// boundary through all points (thesis Chapter 5, Algorithm 5.1).
#pragma once

#include "core/progress.h"
#include "reconstruct/delaunay_complex.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace scanstation {

/// Which removable face goes first.
enum class ConstrictionCriterion {
  gamma_indicator,      ///< smallest γ-indicator (Definitions 5.1, 5.2), the thesis' rule
  minimal_area_change,  ///< smallest Expression (4.1), the baseline of §4.3.3 / §5.6
  /// Expression (4.1) plus a quarter of the mean γ-indicator of the cell's
  /// boundary faces: the area criterion, steered by the γ-indicator where
  /// area changes tie (regular rings of a surface of revolution)
  area_change_and_gamma,
};

struct ConstrictionOptions {
  ConstrictionCriterion criterion = ConstrictionCriterion::gamma_indicator;
  /// Further removals once every point is on the boundary (§5.3: "there is no
  /// general rule telling how long to continue", e.g. the candlestick).
  std::size_t extra_removals = 0;
  /// Once every point is on the boundary, continue while the smallest
  /// selection key (γ-indicator, or sum of two in 3D) is below this value.
  std::optional<double> until_indicator;
  /// Constrained constriction (§5.7): faces (#K by D vertex indices, edges in
  /// 2D, triangles in 3D) that must never be deleted. Each must be a face of
  /// the Delaunay triangulation (InvalidInput names the first that is not).
  Eigen::MatrixXi keep;
  /// γ-guided constriction (3D): also keep every face whose γ-indicators
  /// with respect to its two opposite vertices (1 across the hull) are both
  /// at least guide_c0 and one at least guide_c1; nullopt: off.
  std::optional<double> guide_c1;
  double guide_c0 = 0.0;
  /// One entry per Delaunay cell (or empty): −1, or the rank of a cell known
  /// to lie outside the object, e.g. its depth along a line of sight
  /// (reconstruct/line_of_sight.h). Removable ranked cells go before all
  /// others, lower ranks first — the carving advances from where the camera
  /// looked in — the γ-guide does not hold them, and once every point is on
  /// the boundary constriction goes on while one is removable.
  std::vector<int> carve_first;
  /// Fraction of the points on the boundary so far.
  ProgressCallback progress;
};

/// boundary           #B by D: the boundary faces. 2D: directed edges (a, b)
///                    with the enclosed region on their left (a counter-clockwise
///                    polygon); 3D: triangles counter-clockwise seen from outside.
/// kept               per Delaunay cell, 1 when it is still in the pruned graph:
///                    the cells kept triangulate the enclosed region (§5.8)
/// interior_vertices  vertices not on the boundary (empty when constriction
///                    succeeded; else the ones it could not reach, §5.4)
template <int D>
struct Constriction {
  Eigen::Matrix<int, Eigen::Dynamic, D> boundary;
  std::vector<char> kept;
  std::vector<int> interior_vertices;
  std::size_t removed_cells = 0;
  bool all_on_boundary = false;
  std::size_t guide_faces = 0;  ///< faces γ-guided constriction kept (of those it was asked about)
};

/// Removes boundary cells of the Delaunay complex one at a time, always the
/// removable one with the smallest γ-indicator (Definitions 5.1, 5.2; the
/// selection rules of §5.2 and §5.3), until every point is on the boundary or
/// nothing is removable. Removability keeps the boundary a simple polygon /
/// a closed 2-manifold polyhedron of genus 0: in 2D a triangle with one
/// boundary edge whose opposite vertex is not yet on the boundary; in 3D a
/// tetrahedron with one boundary triangle whose opposite vertex is not on the
/// boundary, or with two boundary triangles whose opposite edge is not.
Constriction<2> constrict(const DelaunayComplex<2>& complex, const ConstrictionOptions& options = {});
Constriction<3> constrict(const DelaunayComplex<3>& complex, const ConstrictionOptions& options = {});

/// The γ-guide's decisions (ConstrictionOptions::guide_c1) on the four faces
/// of one tetrahedron: functions of the cell and its neighbour across the
/// face (none: the convex hull) alone. Whoever keeps them from one
/// constriction to the next clears a face's bits where its neighbour changed.
struct GuideMemo {
  std::uint8_t known = 0;  ///< bit i: the guide decided face i
  std::uint8_t keep = 0;   ///< bit i: the guide kept face i
};

/// Where constriction of part of a complex starts (incremental use,
/// reconstruct/incremental_constriction.h), one flag per cell / point:
/// kept    0: the cell is already removed (outside); empty: every cell is kept
///         (the convex hull, line 2 of Algorithm 5.1)
/// frozen  1: the cell is never removed; empty: none is
/// exempt  1: the point need not reach the boundary for constriction to stop
/// guides  if given, one GuideMemo per cell: read at the start, so that a
///         face an earlier constriction decided is not decided again, and
///         updated with this one's decisions (3D, γ-guided, no faces to
///         keep; ignored otherwise)
struct ConstrictionStart {
  std::vector<char> kept;
  std::vector<char> frozen;
  std::vector<char> exempt;
  std::vector<GuideMemo>* guides = nullptr;
};

/// Constriction (as above) from a given state: the boundary is the faces
/// between kept cells and removed cells (or the outside); it stops when every
/// point of a kept cell that is not exempt is on the boundary. The kept cells
/// must bound a ball for the result to be a closed genus-0 surface.
Constriction<3> constrict(const DelaunayComplex<3>& complex, const ConstrictionStart& start,
                          const ConstrictionOptions& options = {});

/// The pruned graph given by `kept` (one flag per Delaunay cell) as a
/// constriction result: the oriented faces between kept and removed (or
/// outside) cells, and the points on none of them.
Constriction<2> pruned_boundary(const DelaunayComplex<2>& complex, std::vector<char> kept);
Constriction<3> pruned_boundary(const DelaunayComplex<3>& complex, std::vector<char> kept);

/// The γ-indicator (reconstruct/gamma_indicator.h) of the face of `cell`
/// opposite its local vertex `face`, with respect to that vertex.
double gamma_indicator(const DelaunayComplex<2>& complex, int cell, int face);
double gamma_indicator(const DelaunayComplex<3>& complex, int cell, int face);

}  // namespace scanstation
